#pragma once
// Synthetic run directories for the compare tests: whole records
// (JobRecord, tests/record/sample_records.h) with the frame samples, passes
// and errors that `compare` and the CI writers read, and a results.jsonl.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "../record/sample_records.h"
#include "record/job_record.h"

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

// An ok record with frame samples, per-pass detail for a "depth" and a
// "lookup" pass (the first 40 % and 20 % of each frame) and visibility RMSE
// values.
inline record::JobRecord make_record(const std::string& job_id, const std::vector<double>& frame,
                                     double rmse, double penumbra_rmse,
                                     const std::string& run_id = "synthetic") {
  std::vector<double> depth, lookup, technique;
  for (double f : frame) {
    depth.push_back(0.4 * f);
    lookup.push_back(0.2 * f);
    technique.push_back(0.6 * f);
  }
  record::JobRecord r = identity_record("grid", "320x240", "synthetic");
  r.job_id = job_id;
  r.run_id = run_id;
  r.timing = coarse_timing(frame, technique);
  add_fine_timing(*r.timing, {{"depth", depth}, {"lookup", lookup}});
  record::MetricsRecord m;
  m.visibility.all.rmse = rmse;
  m.visibility.all.psnr = -20 * std::log10(rmse);
  m.visibility.penumbra.rmse = penumbra_rmse;
  m.visibility.geometry = m.visibility.all;  // compare's default region
  r.metrics = m;
  return r;
}

// The same records as measured on another machine: another CPU model and,
// when given, another GL renderer string; the host fingerprint follows.
inline std::vector<record::JobRecord> on_host(std::vector<record::JobRecord> records,
                                              const std::string& cpu_model,
                                              const std::string& gl_renderer = "") {
  for (auto& r : records) {
    r.host.cpu->model = cpu_model;
    if (!gl_renderer.empty()) r.gl_renderer = gl_renderer;
    r.host.fingerprint = record::host_fingerprint(r.host, r.gl_renderer, r.gl_version);
  }
  return records;
}

// An ok record whose frames were each timed next to a frame of the control
// job `control` (timing.control): frame i = control_ms[i] × ratio[i], the
// technique two thirds of it.
inline record::JobRecord make_controlled_record(const std::string& job_id,
                                                const std::vector<double>& control_ms,
                                                const std::vector<double>& ratio, double rmse,
                                                const std::string& control = "none") {
  const size_t n = std::min(control_ms.size(), ratio.size());
  std::vector<double> frame(n), technique(n), control_frame(n), ratios(n);
  for (size_t i = 0; i < n; ++i) {
    frame[i] = control_ms[i] * ratio[i];
    technique[i] = frame[i] * 2 / 3;
    control_frame[i] = control_ms[i];
    ratios[i] = frame[i] / control_ms[i];
  }
  record::JobRecord r = make_record(job_id, frame, rmse, 2 * rmse);
  r.timing->technique = record::Series::of(technique);
  record::ControlTiming c;
  c.technique = control;
  c.frame = record::Series::of(control_frame);
  c.frame_ratio = record::Series::of(ratios);
  r.timing->control = std::move(c);
  return r;
}

// The records as measured against a Monte Carlo reference of `spp` samples
// per pixel whose cache key is `cache_key` (record["reference"]).
inline record::ReferenceRecord mc_reference(int spp, const std::string& cache_key) {
  record::ReferenceRecord ref;
  ref.method = "embree_stratified_packet16";
  ref.spp = spp;
  ref.seed = 1;
  ref.embree_isa = "avx2";
  ref.cache_key = cache_key;
  return ref;
}
inline std::vector<record::JobRecord> against(std::vector<record::JobRecord> records,
                                              const record::ReferenceRecord& reference) {
  for (auto& r : records) r.reference = reference;
  return records;
}

inline std::filesystem::path temp_dir(const std::string& name) {
  // The process id keeps the shards of test_compare, run side by side, apart.
  auto dir = std::filesystem::temp_directory_path() /
             ("shadowbench_test_compare-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string write_run(const std::string& name,
                             const std::vector<record::JobRecord>& records) {
  const auto dir = temp_dir(name);
  std::ofstream out(dir / "results.jsonl");
  for (const auto& r : records) out << r.to_json().dump() << "\n";
  return dir.string();
}

}  // namespace sb::test
