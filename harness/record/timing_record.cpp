#include "record/timing_record.h"

#include <algorithm>

#include "record/timing_stats.h"

namespace sb {

using json = nlohmann::json;

TimingSeries TimingSeries::of(const std::vector<double>& samples) {
  const TimingStats s = summarize(samples);
  TimingSeries t;
  t.count = static_cast<std::int64_t>(s.count);
  t.median_ms = s.median;
  t.p10_ms = s.p10;
  t.p90_ms = s.p90;
  t.mean_ms = s.mean;
  t.min_ms = s.min;
  t.max_ms = s.max;
  t.cv = s.cv;
  t.samples_ms = samples;
  return t;
}

json TimingSeries::to_json() const {
  json samples = json::array();
  for (const double v : samples_ms) samples.push_back(json_number(v));
  return {{"count", count},
          {"median_ms", json_number(median_ms)},
          {"p10_ms", json_number(p10_ms)},
          {"p90_ms", json_number(p90_ms)},
          {"mean_ms", json_number(mean_ms)},
          {"min_ms", json_number(min_ms)},
          {"max_ms", json_number(max_ms)},
          {"cv", json_number(cv)},
          {"samples_ms", std::move(samples)}};
}

TimingSeries TimingSeries::from_json(const Fields& f) {
  TimingSeries t;
  t.count = f.get<std::int64_t>("count");
  t.median_ms = f.get<double>("median_ms");
  t.p10_ms = f.get<double>("p10_ms");
  t.p90_ms = f.get<double>("p90_ms");
  t.mean_ms = f.get<double>("mean_ms");
  t.min_ms = f.get<double>("min_ms");
  t.max_ms = f.get<double>("max_ms");
  t.cv = f.get<double>("cv");
  t.samples_ms = f.get<std::vector<double>>("samples_ms");
  return t;
}

RatioSeries RatioSeries::of(const std::vector<double>& samples) {
  const TimingStats s = summarize(samples);
  RatioSeries r;
  r.count = static_cast<std::int64_t>(s.count);
  r.median = s.median;
  r.p10 = s.p10;
  r.p90 = s.p90;
  r.mean = s.mean;
  r.min = s.min;
  r.max = s.max;
  r.cv = s.cv;
  r.samples = samples;
  return r;
}

json RatioSeries::to_json() const {
  json out = json::array();
  for (const double v : samples) out.push_back(json_number(v));
  return {{"count", count},          {"median", json_number(median)}, {"p10", json_number(p10)},
          {"p90", json_number(p90)}, {"mean", json_number(mean)},     {"min", json_number(min)},
          {"max", json_number(max)}, {"cv", json_number(cv)},         {"samples", std::move(out)}};
}

RatioSeries RatioSeries::from_json(const Fields& f) {
  RatioSeries r;
  r.count = f.get<std::int64_t>("count");
  r.median = f.get<double>("median");
  r.p10 = f.get<double>("p10");
  r.p90 = f.get<double>("p90");
  r.mean = f.get<double>("mean");
  r.min = f.get<double>("min");
  r.max = f.get<double>("max");
  r.cv = f.get<double>("cv");
  r.samples = f.get<std::vector<double>>("samples");
  return r;
}

json ControlTiming::to_json() const {
  return {
      {"technique", technique}, {"frame", frame.to_json()}, {"frame_ratio", frame_ratio.to_json()}};
}

ControlTiming ControlTiming::from_json(const Fields& f) {
  ControlTiming c;
  c.technique = f.get<std::string>("technique");
  c.frame = TimingSeries::from_json(f.object("frame"));
  c.frame_ratio = RatioSeries::from_json(f.object("frame_ratio"));
  return c;
}

namespace {

json series_map(const std::map<std::string, TimingSeries>& m) {
  json out = json::object();
  for (const auto& [name, series] : m) out[name] = series.to_json();
  return out;
}

std::map<std::string, TimingSeries> series_map(const Fields& f) {
  std::map<std::string, TimingSeries> out;
  for (const auto& name : f.keys()) out[name] = TimingSeries::from_json(f.object(name));
  return out;
}

}  // namespace

json TimingRecord::to_json() const {
  json t = {{"compile_frames", compile_frames}, {"warmup_frames", warmup_frames},
            {"timed_frames", timed_frames},     {"pass_timing", pass_timing},
            {"frame", frame.to_json()},         {"technique", technique.to_json()}};
  if (!shared.empty()) t["shared"] = series_map(shared);
  if (fine) {
    t["passes"] = series_map(fine->passes);
    t["pass_order"] = fine->pass_order;
    t["fine"] = {{"frames", fine->frames},
                 {"technique", fine->technique.to_json()},
                 {"frame", fine->frame.to_json()}};
  }
  if (control) t["control"] = control->to_json();
  return t;
}

TimingRecord TimingRecord::from_json(const Fields& f) {
  TimingRecord t;
  t.compile_frames = f.get<int>("compile_frames");
  t.warmup_frames = f.get<int>("warmup_frames");
  t.timed_frames = f.get<int>("timed_frames");
  t.pass_timing = f.get<std::string>("pass_timing");
  t.frame = TimingSeries::from_json(f.object("frame"));
  t.technique = TimingSeries::from_json(f.object("technique"));
  if (const auto shared = f.find_object("shared")) t.shared = series_map(*shared);
  // Per-pass detail comes as three members together, or not at all.
  if (f.has("fine") || f.has("passes") || f.has("pass_order")) {
    FineTiming fine;
    fine.passes = series_map(f.object("passes"));
    fine.pass_order = f.get<std::vector<std::string>>("pass_order");
    for (size_t i = 0; i < fine.pass_order.size(); ++i)
      if (!fine.passes.count(fine.pass_order[i]))
        throw RecordError(f.pointer_of("pass_order") + "/" + std::to_string(i),
                          "names the pass \"" + fine.pass_order[i] + "\", which \"passes\" lacks");
    for (const auto& [name, series] : fine.passes)
      if (std::find(fine.pass_order.begin(), fine.pass_order.end(), name) == fine.pass_order.end())
        throw RecordError(f.object("passes").pointer_of(name),
                          "a pass that \"pass_order\" does not name");
    const Fields detail = f.object("fine");
    fine.frames = detail.get<int>("frames");
    fine.technique = TimingSeries::from_json(detail.object("technique"));
    fine.frame = TimingSeries::from_json(detail.object("frame"));
    t.fine = std::move(fine);
  }
  if (const auto control = f.find_object("control")) {
    t.control = ControlTiming::from_json(*control);
    // Frame i of the control was timed next to frame i of the job.
    if (t.control->frame.samples_ms.size() != t.frame.samples_ms.size())
      throw RecordError(control->object("frame").pointer_of("samples_ms"),
                        "has " + std::to_string(t.control->frame.samples_ms.size()) +
                            " samples, timing.frame has " +
                            std::to_string(t.frame.samples_ms.size()) + ": they come in pairs");
  }
  return t;
}

}  // namespace sb
