#include "run/runner.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/image_codec.h"
#include "core/names.h"
#include "gl/context.h"
#include "plan/plan.h"
#include "plan/plan_json.h"
#include "record/spec_changes.h"
#include "results/report.h"
#include "run/io_trace.h"
#include "run/isolated_work.h"
#include "run/job_executor.h"
#include "run/job_identity.h"
#include "run/job_line.h"
#include "run/progress.h"
#include "run/session_info.h"
#include "store/results_store.h"
#include "store/run_lock.h"

namespace sb::run {

using config::Experiment;
using core::write_file_atomically;
using plan::drop_scene_data;
using plan::make_plan;
using plan::Plan;
using plan::plan_to_json;
using plan::PlannedJob;
using record::JobRecord;
using record::JobStatus;
using record::rerun_reason;
using results::write_reports;
using store::json_text;
using store::ResultsStore;
using store::RunFolderLock;

Isolation isolation_from_string(const std::string& s) {
  if (s == "none") return Isolation::None;
  if (s == "group") return Isolation::Group;
  if (s == "job") return Isolation::Job;
  throw std::invalid_argument("expected job, group or none, found '" + s + "'");
}

std::string to_string(Isolation isolation) {
  switch (isolation) {
    case Isolation::None:
      return "none";
    case Isolation::Group:
      return "group";
    case Isolation::Job:
      return "job";
  }
  return "?";
}

void RunSummary::add_rerun_reason(const std::string& why) {
  for (auto& [reason, count] : rerun_reasons)
    if (reason == why) {
      ++count;
      return;
    }
  rerun_reasons.emplace_back(why, 1);
}

namespace {

using json = nlohmann::json;

// Where every job's events end, whichever process rendered it: the results
// store, the progress line and the log.
class StoreEvents final : public ParentEvents {
 public:
  StoreEvents(ResultsStore& store, Progress& progress, RunSummary& summary, bool quiet,
              size_t total)
      : store_(store), progress_(progress), summary_(summary), quiet_(quiet), total_(total) {}

  void log(const std::string& line) override {
    if (quiet_) return;
    const ParentIoSpan io("log");
    progress_.clear();
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    progress_.draw();
  }
  void backend(const GlIdentity& gl) override {
    const std::string line =
        "backend " + gl.platform + ", " + gl.renderer + ", timing " + gl.timing_source;
    if (line != last_backend_) log(line);  // once, though every child makes a context
    last_backend_ = line;
  }
  void scene_planned(const std::string& scene, const std::vector<std::string>& lines,
                     const std::string& bad_input) override {
    if (!planned_.insert(scene).second) return;  // each child reports its scene again
    for (const auto& l : lines) {
      std::string line = "scene " + scene;
      line += ": ";
      line += l;
      log(line);
    }
    if (!bad_input.empty()) {
      // A bad scene file: its jobs fail, the other scenes still run, and the
      // run's exit code says "bad input". Said even with --quiet.
      ++summary_.bad_input;
      const ParentIoSpan io("bad input");
      progress_.clear();
      std::fprintf(stderr, "shadowbench: error: %s\n", bad_input.c_str());
    }
  }
  void phase(const std::string& scene, const std::string& resolution,
             const std::string& what) override {
    const ParentIoSpan io("progress");
    progress_.start_job(scene, resolution, what);
  }
  void job_started(const JobRecord& base) override {
    const ParentIoSpan io("progress");
    progress_.start_job(base.scene_variant, base.resolution, base.technique_variant);
  }
  void job_finished(JobRecord record) override {
    if (!record.finished_at) record.finished_at = now_iso8601();
    if (record.status == JobStatus::Ok) ++summary_.ok;
    if (record.status == JobStatus::Skipped) ++summary_.skipped;
    if (record.status == JobStatus::Failed) ++summary_.failed;
    const ParentIoSpan io("record " + record.job_id, true);
    store_.put(record);
    ++done_;
    // Jobs that rendered carry their duration; the rest took no time.
    if (record.duration_s)
      progress_.finish_job();
    else
      progress_.add_done_without_running(1);
    log(job_line(record, done_, total_));
  }
  void child_stderr(const std::string& line) override {
    const ParentIoSpan io("stderr");
    progress_.clear();
    std::fprintf(stderr, "%s\n", line.c_str());
    progress_.draw();
  }
  void resumed(bool retimed) {
    if (retimed) {  // finished again, in this session, by job_finished
      ++summary_.retimed;
      return;
    }
    ++summary_.resumed;
    ++done_;
    progress_.add_done_without_running(1);
  }

 private:
  ResultsStore& store_;
  Progress& progress_;
  RunSummary& summary_;
  bool quiet_;
  size_t total_;
  size_t done_ = 0;
  std::string last_backend_;
  std::set<std::string> planned_;
};

class Runner {
 public:
  Runner(const Experiment& e, const RunOptions& o)
      : e_(e),
        o_(with_session(o)),
        lock_(o.run_dir),
        store_(o.run_dir),
        progress_(stderr, !o.quiet && isatty(fileno(stderr)), 0) {}

  RunSummary run() {
    // The one plan, made before any GL context and kept beside the records:
    // every job's outcome, cost and shard. Children are forked, so they read
    // the same PlannedJobs, and the scenes the plan built and kept: each
    // scene is built once in the run, in this process.
    plan_ = make_plan(e_, o_.shard.count, o_.keep_scene_bytes);
    o_.only.check(plan_);
    {
      const ParentIoSpan io("plan");
      write_file_atomically((std::filesystem::path(store_.dir()) / "plan.json").string(),
                            json_text(plan_to_json(e_, plan_), 2) + "\n", "plan.json: ");
    }
    // This shard's jobs (all of them unless --shard), in plan order; of
    // them, the ones --only selects run. The records keep the shard's order.
    std::vector<const PlannedJob*> jobs;
    std::vector<std::string> order;
    for (const PlannedJob& j : plan_.jobs)
      if (j.shard == o_.shard.index) {
        if (o_.only.selects(j.id))
          jobs.push_back(&j);
        else
          ++summary_.unselected;
        order.push_back(j.id);
      }
    store_.set_order(order);
    // Scenes none of those jobs is in (another shard's, or unselected) are
    // not held for nothing.
    std::vector<bool> used(plan_.scenes.size(), false);
    for (const PlannedJob* j : jobs) used[j->scene] = true;
    for (size_t s = 0; s < used.size(); ++s)
      if (!used[s]) drop_scene_data(plan_.scenes[s]);
    progress_ = Progress(stderr, !o_.quiet && isatty(fileno(stderr)), jobs.size());
    StoreEvents events(store_, progress_, summary_, o_.quiet, jobs.size());
    report_untrusted_records();
    slow_parent_io_ns();  // a malformed test-only variable is bad input before any job
    // A run killed between a record and results.jsonl left the two apart.
    {
      const ParentIoSpan io("index");
      store_.rewrite_index();
    }

    embree_ = choose_embree(e_, o_);
    limits_.job_seconds = o_.job_seconds.value_or(e_.limits.job_seconds);
    limits_.setup_seconds = o_.setup_seconds.value_or(e_.limits.setup_seconds);

    // Plan order is scene-major, then resolution: a scene's jobs are
    // consecutive, and so are a (scene, resolution)'s.
    for (size_t next = 0; next < jobs.size();) {
      const size_t scene = jobs[next]->scene;
      std::vector<ResolutionWork> work;
      for (; next < jobs.size() && jobs[next]->scene == scene; ++next) {
        const PlannedJob& j = *jobs[next];
        const JobRecord* retime = nullptr;
        if (resumable(j, events)) {
          if (o_.retime && store_.finished(j.id)->status == JobStatus::Ok)
            retime = store_.finished(j.id);
          events.resumed(retime != nullptr);
          if (retime == nullptr) continue;
        }
        if (work.empty() || work.back().resolution != j.resolution)
          work.push_back({j.resolution, {}, &plan_.scenes[j.scene].scene.inputs});
        work.back().jobs.push_back(&j);
        if (retime != nullptr) work.back().retime[j.id] = retime;
      }
      if (!work.empty()) run_scene(scene, work, events);
      drop_scene_data(plan_.scenes[scene]);  // done with: the next scenes' memory
    }
    progress_.clear();
    {
      const ParentIoSpan io("reports");
      write_reports(store_.dir(), store_.records(), e_.name + " (" + o_.run_id + ")");
    }
    return summary_;
  }

 private:
  void run_scene(size_t scene, const std::vector<ResolutionWork>& work, StoreEvents& events) {
    if (o_.isolation == Isolation::None) {
      // One GL context for the whole run, made when the first job needs it.
      if (!executor_) executor_ = std::make_unique<JobExecutor>(e_, o_, embree_, events);
      executor_->run_scene(scene, work, &plan_.scenes[scene]);
      return;
    }
    load_child_libraries();
    for (const ResolutionWork& w : work) {
      std::vector<ResolutionWork> pieces;
      if (o_.isolation == Isolation::Group)
        pieces.push_back(w);
      else
        for (const PlannedJob* j : w.jobs) {
          ResolutionWork piece = w;
          piece.jobs = {j};
          pieces.push_back(std::move(piece));
        }
      for (const ResolutionWork& piece : pieces) {
        const IsolatedOutcome out =
            run_isolated(e_, o_, embree_, scene, piece, &plan_.scenes[scene], limits_, events);
        summary_.crashed += out.crashed;
        summary_.timed_out += out.timed_out;
      }
    }
  }

  // What every child would otherwise open for itself, opened once here and
  // inherited by each fork: the GL backend's library (libOSMesa brings in
  // LLVM) and, when images are written, the image codec (OpenImageIO, ~0.4 s).
  // A child that still cannot open one says why in its jobs' records.
  void load_child_libraries() const {
    gl::load_backend_library(o_.backend);
    if (!o_.write_images) return;
    try {
      core::image_codec();
    } catch (const std::runtime_error&) {  // NOLINT(bugprone-empty-catch): said by the child
    }
  }

  bool resumable(const PlannedJob& j, StoreEvents& events) {
    const std::string& id = j.id;
    const JobRecord* done = store_.finished(id);
    if (done == nullptr) return false;
    const json spec =
        job_spec(e_, o_, embree_, e_.scenes[j.scene], plan_.scenes[j.scene].scene.inputs,
                 e_.resolutions[j.resolution], e_.techniques[j.technique]);
    const std::string why = rerun_reason(*done, spec, job_spec_hash(spec));
    if (why.empty()) return true;
    ++summary_.respecified;
    summary_.add_rerun_reason(why);
    events.log("job " + id + ": runs again: " + why);
    return false;
  }

  // Record files an earlier run left that cannot be trusted (torn by a
  // crash of the disk, edited, of another schema): said, and their jobs rerun.
  void report_untrusted_records() {
    for (const std::string& problem : store_.untrusted()) {
      ++summary_.bad_records;
      progress_.clear();
      std::fprintf(stderr, "shadowbench: warning: %s; its job runs again\n", problem.c_str());
    }
  }

  // The options with this run's session: what every record it writes names.
  static RunOptions with_session(const RunOptions& o) {
    RunOptions out = o;
    if (!out.session) out.session = start_session();
    return out;
  }

  const Experiment& e_;
  const RunOptions o_;
  RunFolderLock lock_;  // before store_: nothing is read until the folder is ours
  ResultsStore store_;
  Progress progress_;
  EmbreeChoice embree_;
  TimeLimits limits_;
  RunSummary summary_;
  Plan plan_;                              // what ResolutionWork points into
  std::unique_ptr<JobExecutor> executor_;  // isolation none
};

}  // namespace

RunSummary run_experiment(const Experiment& experiment, const RunOptions& options) {
  return Runner(experiment, options).run();
}

}  // namespace sb::run
