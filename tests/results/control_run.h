#pragma once
// Records of one (scene, resolution) as configs/ci.json's run makes them,
// with the medians and errors docs/paper.md shows (llvmpipe, 2-core VM), and
// `none` as every job's timing control (config frames.control): the
// fastest, and by default the least accurate. Each job has 30 frames spread
// ±5 % around its median, each timed next to a control frame, and
// timing.control.frame_ratio holds their quotients.
#include <cmath>
#include <string>
#include <vector>

#include "../record/sample_records.h"
#include "record/job_record.h"

namespace sb::test {

// Frame i of 30 of a job: its median times 1 + 0.1 (((i a) mod 31) / 30 - 0.5),
// so that jobs with different `a` are differently shuffled (the formula of
// tests/results/rank_ties_values.py).
inline std::vector<double> spread_samples(double median, int a, int n = 30) {
  std::vector<double> out;
  out.reserve(size_t(n));
  for (int i = 0; i < n; ++i)
    out.push_back(median * (1 + 0.1 * (double((i * a) % 31) / 30.0 - 0.5)));
  return out;
}

struct ControlRunJob {
  const char* technique;
  double frame_ms, rmse, penumbra_rmse, ssim, flip;
};

inline std::vector<ControlRunJob> control_run_jobs(double control_rmse) {
  return {{"none", 1.02, control_rmse, 0.5, 0.5, 0.09},
          {"shadow_map/size=1024", 11.8, 0.0932, 0.268, 0.921, 0.0359},
          {"pcf_box/k=3,size=1024", 12.3, 0.0723, 0.207, 0.940, 0.0328},
          {"pcss/size=1024", 14.1, 0.0208, 0.0576, 0.992, 0.0138},
          {"vsm/size=512,prefilter=gauss,k=9", 27.7, 0.0270, 0.0759, 0.986, 0.0207},
          {"shadow_volume/mode=zpass", 14.7, 0.0927, 0.267, 0.921, 0.0358}};
}

// The group's records; `control_rmse` the control's error (0.30: the worst).
inline std::vector<record::JobRecord> control_run_records(
    double control_rmse = 0.30, const std::string& scene = "sphere_grid/light_size=2.0",
    const std::string& res = "320x240") {
  std::vector<record::JobRecord> out;
  const std::vector<double> control = spread_samples(1.02, 2);
  int a = 3;
  for (const ControlRunJob& j : control_run_jobs(control_rmse)) {
    record::JobRecord r = identity_record(scene, res, j.technique);
    const std::vector<double> frame =
        std::string(j.technique) == "none" ? control : spread_samples(j.frame_ms, a++);
    std::vector<double> technique, ratio;
    for (size_t i = 0; i < frame.size(); ++i) {
      technique.push_back(frame[i] * 0.5);
      ratio.push_back(frame[i] / control[i]);
    }
    r.timing = coarse_timing(frame, technique);
    record::ControlTiming c;
    c.technique = "none";
    c.frame = record::Series::of(control);
    c.frame_ratio = record::Series::of(ratio);
    r.timing->control = c;
    record::MetricsRecord m;
    m.visibility.all.rmse = j.rmse;
    m.visibility.all.mae = j.rmse / 2;
    m.visibility.all.max_error = 1.0;
    m.visibility.all.psnr = -20 * std::log10(j.rmse);
    m.visibility.all.ssim = j.ssim;
    m.visibility.all.frac_over_005 = j.rmse / 3;
    m.visibility.penumbra.rmse = j.penumbra_rmse;
    m.visibility.geometry = m.visibility.all;
    m.flip_shaded = j.flip;
    r.metrics = m;
    out.push_back(r);
  }
  return out;
}

// Pointers to `records`, as a group of them.
inline std::vector<const record::JobRecord*> record_pointers(
    const std::vector<record::JobRecord>& records) {
  std::vector<const record::JobRecord*> out;
  out.reserve(records.size());
  for (const record::JobRecord& r : records) out.push_back(&r);
  return out;
}

}  // namespace sb::test
