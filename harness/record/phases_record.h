#pragma once
// record["phases_s"]: where a rendered job's wall time (duration_s) went, in
// seconds of steady_clock, and record["overhead_s"], the part of it that
// measures nothing (docs/results.md, docs/performance.md):
//
//   "prepare"    create() and prepare(): shaders, maps, buffers
//   "frames"     every frame the job renders: the compile frame, the warm-up
//                and timed frames, the control frames next to them, and
//                --pass-timing fine's frames
//   "measure"    reading V back, checking it, shading it, its metrics
//                against the reference(s) and its classes; meanwhile the
//                images that need no figure are written
//   "images"     writing the images: what is left of it after "measure"
//   "stability"  the "stability" block's extra frames and references
//
//   overhead_s = duration_s - frames - stability: what the harness spends
//   on a job besides the frames it was asked to render and measure.
#include <nlohmann/json.hpp>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

struct PhasesRecord {
  static constexpr RecordDoc kSchema{"PhasesRecord", "where a rendered job's `duration_s` went"};

  double prepare = 0, frames = 0, measure = 0, images = 0, stability = 0;

  template <class V>
  static void describe(V& v) {
    v.field("prepare", &PhasesRecord::prepare, {"s", "create and prepare the technique"});
    v.field("frames", &PhasesRecord::frames,
            {"s",
             "every frame it rendered: the compile frame, warm-up and timed frames, the "
             "control frames next to them, `--pass-timing fine`'s; for a temporal technique "
             "also the second `prepare()` and the `frames.history` frames its V is measured on"});
    v.field("measure", &PhasesRecord::measure,
            {"s",
             "read-back, checks, shading, metrics, classes; the images that need no figure are "
             "written meanwhile"});
    v.field("images", &PhasesRecord::images,
            {"s", "writing the images: what is left of it once the metrics are done"});
    v.field("stability", &PhasesRecord::stability,
            {"s", "the stability block's frames and references"});
  }

  // prepare + measure + images, plus whatever of `duration` no phase
  // covers (GL state resets, record keeping).
  double overhead(double duration) const { return duration - frames - stability; }

  nlohmann::json to_json() const;
  static PhasesRecord from_json(const Fields& f);
};

}  // namespace sb::record
