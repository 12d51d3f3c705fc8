#pragma once
// Records with known numbers for the paper-export tests: one scene at one
// resolution, a tie, a higher-is-better column with +inf, LaTeX's special
// characters in a name, and a skipped and a failed job.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../record/sample_records.h"
#include "record/job_record.h"

namespace sb::test {

inline constexpr const char* kNastyTechnique = "odd_one/a&b=50%,c#d={x}~^\\$";

struct LatexJob {
  const char* technique;
  record::JobStatus status;
  double frame_ms, rmse, penumbra_rmse, ssim, psnr;
};

// frame_ms: 2.5 is best, once; rmse: 0.0123 twice (a tie); ssim: 0.97 best
// (higher is better); psnr: +inf best (an exact match); the failed job has
// the lowest numbers of all, and must not be bold.
inline std::vector<LatexJob> latex_jobs() {
  const double inf = std::numeric_limits<double>::infinity();
  using S = record::JobStatus;
  return {{"none", S::Ok, 2.5, 0.25, 0.5, 0.41, 12.0},
          {"pcf_box/k=3,size=1024", S::Ok, 9.0, 0.0123, 0.031, 0.93, 38.2},
          {kNastyTechnique, S::Ok, 12.0, 0.0123, 0.0299, 0.97, inf},
          {"shadow_volume/mode=zpass", S::Skipped, 0, 0, 0, 0, 0},
          {"vsm/k=9,prefilter=gauss", S::Failed, 1.0, 0.001, 0.001, 1.0, 99.0}};
}

inline std::vector<record::JobRecord> latex_records(const std::string& scene = "plates/layout=edge",
                                                    const std::string& res = "64x48") {
  std::vector<record::JobRecord> out;
  for (const LatexJob& j : latex_jobs()) {
    record::JobRecord r = identity_record(scene, res, j.technique, j.status);
    if (j.status == record::JobStatus::Skipped) {
      r.reason = "casters are not closed";
    } else {
      if (j.status == record::JobStatus::Failed) r.reason = "GL error";
      r.timing = coarse_timing({j.frame_ms, j.frame_ms * 1.01, j.frame_ms * 0.99},
                               {j.frame_ms / 2, j.frame_ms / 2, j.frame_ms / 2});
      record::MetricsRecord m;
      m.visibility.all.rmse = j.rmse;
      m.visibility.all.mae = j.rmse / 2;
      m.visibility.all.max_error = 1.0;
      m.visibility.all.psnr = j.psnr;
      m.visibility.all.ssim = j.ssim;
      m.visibility.all.frac_over_005 = 0.01;
      m.visibility.penumbra.rmse = j.penumbra_rmse;
      m.visibility.geometry = m.visibility.all;
      r.metrics = m;
    }
    out.push_back(r);
  }
  return out;
}

// A run folder holding `records` as results.jsonl.
inline void write_run(const std::filesystem::path& run_dir,
                      const std::vector<record::JobRecord>& records) {
  std::filesystem::create_directories(run_dir);
  std::ofstream out(run_dir / "results.jsonl");
  for (const auto& r : records) out << r.to_json().dump() << "\n";
}

}  // namespace sb::test
