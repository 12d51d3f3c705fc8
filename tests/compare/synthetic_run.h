#pragma once
// Synthetic run directories for the compare tests: records with the fields
// `compare` and the CI writers read (docs/results.md), and a results.jsonl.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "record/timing_record.h"

namespace sb::test {

// n frame times around `median_ms` with uniform noise of ±noise (relative);
// std::mt19937's output is fixed by the standard, so the samples are too.
inline std::vector<double> noisy_samples(double median_ms, double noise, int n, uint32_t seed) {
  std::mt19937 gen(seed);
  std::vector<double> v;
  for (int i = 0; i < n; ++i) {
    const double u = double(gen()) / 4294967295.0;  // [0, 1]
    v.push_back(median_ms * (1 + noise * (2 * u - 1)));
  }
  return v;
}

inline nlohmann::json timing_json(const std::vector<double>& samples) {
  return TimingSeries::of(samples).to_json();
}

// An ok record with frame samples, a "depth" and a "lookup" pass (the first
// 40 % and 20 % of each frame) and visibility RMSE values.
inline nlohmann::json make_record(const std::string& job_id, const std::vector<double>& frame,
                                  double rmse, double penumbra_rmse,
                                  const std::string& run_id = "synthetic") {
  std::vector<double> depth, lookup;
  for (double f : frame) {
    depth.push_back(0.4 * f);
    lookup.push_back(0.2 * f);
  }
  nlohmann::json r;
  r["schema_version"] = 1;
  r["run_id"] = run_id;
  r["experiment"] = "synthetic";
  r["job_id"] = job_id;
  r["status"] = "ok";
  r["timing"]["warmup_frames"] = 1;
  r["timing"]["timed_frames"] = frame.size();
  r["timing"]["frame"] = timing_json(frame);
  r["timing"]["pass_order"] = {"depth", "lookup"};
  r["timing"]["passes"]["depth"] = timing_json(depth);
  r["timing"]["passes"]["lookup"] = timing_json(lookup);
  std::vector<double> technique;
  for (size_t i = 0; i < frame.size(); ++i) technique.push_back(depth[i] + lookup[i]);
  r["timing"]["technique"] = timing_json(technique);
  r["metrics"]["visibility"]["all"]["rmse"] = rmse;
  r["metrics"]["visibility"]["all"]["psnr"] = -20 * std::log10(rmse);
  r["metrics"]["visibility"]["penumbra"]["rmse"] = penumbra_rmse;
  return r;
}

inline std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "shadowbench_test_compare" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string write_run(const std::string& name, const std::vector<nlohmann::json>& records) {
  const auto dir = temp_dir(name);
  std::ofstream out(dir / "results.jsonl");
  for (const auto& r : records) out << r.dump() << "\n";
  return dir.string();
}

}  // namespace sb::test
