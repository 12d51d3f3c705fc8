#include "record/timing_record.h"

#include <algorithm>

#include "record/record_json.h"
#include "record/timing_stats.h"

namespace sb::record {

using json = nlohmann::json;

Series Series::of(const std::vector<double>& samples) {
  const TimingStats s = summarize(samples);
  return {static_cast<std::int64_t>(s.count),
          s.median,
          s.p10,
          s.p90,
          s.mean,
          s.min,
          s.max,
          s.cv,
          s.median_ci_lo,
          s.median_ci_hi,
          s.median_ci_rel(),
          s.median_ci_coverage,
          samples};
}

NoiseRecord NoiseRecord::judge(const TimingRecord& t, double threshold) {
  NoiseRecord n;
  n.frame_ci_rel = t.frame.median_ci_rel;
  if (t.control) {
    n.control_frame_ci_rel = t.control->frame.median_ci_rel;
    n.frame_ratio_ci_rel = t.control->frame_ratio.median_ci_rel;
  }
  n.threshold = threshold;
  n.noisy = n.judged_ci_rel() > threshold;
  return n;
}

void FineTiming::check(const FineTiming& t, const Fields& f) {
  for (size_t i = 0; i < t.pass_order.size(); ++i)
    if (!t.passes.count(t.pass_order[i]))
      throw RecordError(f.pointer_of("pass_order") + "/" + std::to_string(i),
                        "names the pass \"" + t.pass_order[i] + "\", which \"passes\" lacks");
  for (const auto& [name, series] : t.passes)
    if (std::find(t.pass_order.begin(), t.pass_order.end(), name) == t.pass_order.end())
      throw RecordError(f.object("passes").pointer_of(name),
                        "a pass that \"pass_order\" does not name");
}

void TimingRecord::check(const TimingRecord& t, const Fields& f) {
  // Frame i of the control was timed next to frame i of the job.
  if (t.control && t.control->frame.samples.size() != t.frame.samples.size())
    throw RecordError(f.object("control").object("frame").pointer_of("samples_ms"),
                      "has " + std::to_string(t.control->frame.samples.size()) +
                          " samples, timing.frame has " + std::to_string(t.frame.samples.size()) +
                          ": they come in pairs");
}

json TimingRecord::to_json() const { return write_record(*this); }
TimingRecord TimingRecord::from_json(const Fields& f) { return read_record<TimingRecord>(f); }

}  // namespace sb::record
