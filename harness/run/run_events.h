#pragma once
// What the job executor tells whoever runs it: log lines, progress, and
// each job's start and record. In one process these go straight to the
// results store (run/runner.cpp); from a child process they cross a pipe as
// JSON lines (run/isolated_work.h), so that a child that dies mid-job
// leaves the parent knowing which job it was in and what it had measured.
#include <string>
#include <string_view>
#include <vector>

#include "record/job_record.h"

namespace sb::run {

struct GlIdentity {
  std::string platform, renderer, version, timing_source;
};

class RunEvents {
 public:
  virtual ~RunEvents() = default;
  virtual void log(const std::string& line) = 0;
  // A GL context was made: what every record of this process names.
  virtual void backend(const GlIdentity& gl) = 0;
  // A scene variant was planned: its plan's log lines, and the InputError's
  // message when its input was bad ("" otherwise). Said once per process
  // that planned it.
  virtual void scene_planned(const std::string& scene, const std::vector<std::string>& log,
                             const std::string& bad_input) = 0;
  // Shared work of a (scene, resolution): "(reference)", "(second reference)".
  virtual void phase(const std::string& scene, const std::string& resolution,
                     const std::string& what) = 0;
  // A job starts rendering; `base` is its record so far (identity, host,
  // reference): what a failed record of it would say.
  virtual void job_started(const record::JobRecord& base) = 0;
  // A job's final record: ok, skipped or failed.
  virtual void job_finished(record::JobRecord record) = 0;
  // A job is about to render its frames: returns once whoever hears these
  // events has done all they asked (records stored, lines printed), so that
  // none of it overlaps a timed frame (docs/robustness.md). In one process
  // every event is done when its call returns.
  virtual void await_listener() {}
  // The phase of the started job it enters ("prepare()", a frame's
  // "render()", "read-back", ...), for the reason of a job whose process
  // dies in it. Costs no I/O: it is said between timed frames.
  virtual void job_phase(std::string_view /*phase*/) {}
};

}  // namespace sb::run
