#pragma once
// Records for tests that read them (report, charts, compare, the CI
// outputs), built as the runner builds them: a JobRecord, then to_json().
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/names.h"
#include "record/job_record.h"

namespace sb::test {

// A record of `status` with every identifying member filled in as `run`
// fills it, and nothing measured: callers add timing, metrics, images.
inline record::JobRecord identity_record(const std::string& scene_variant,
                                         const std::string& resolution,
                                         const std::string& technique_variant,
                                         record::JobStatus status = record::JobStatus::Ok) {
  record::JobRecord r;
  r.run_id = "synthetic";
  r.experiment = "synthetic";
  r.config = "synthetic.json";
  r.config_hash = "0123456789abcdef";
  r.job_id = core::job_id(scene_variant, resolution, technique_variant);
  r.spec_hash = "fedcba9876543210";
  r.scene_variant = scene_variant;
  r.technique_variant = technique_variant;
  r.resolution = resolution;
  std::sscanf(resolution.c_str(), "%dx%d", &r.width, &r.height);
  r.scene.type = scene_variant.substr(0, scene_variant.find('/'));
  r.scene.variant = scene_variant;
  r.technique.name = technique_variant.substr(0, technique_variant.find('/'));
  r.technique.family = r.technique.name;
  r.technique.variant = technique_variant;
  r.backend = "osmesa";
  r.gl_platform = "osmesa";
  r.gl_renderer = "llvmpipe (test)";
  r.gl_version = "4.5 (Core Profile) Mesa";
  r.timing_source = "cpu_glfinish";
  r.host.hardware_threads = 2;
  r.host.cpu = record::CpuRecord{"Synthetic CPU", {"sse4.2", "avx", "avx2", "fma"}, 2};
  r.host.os = "Debian GNU/Linux 12 (bookworm)";
  r.host.fingerprint = record::host_fingerprint(r.host, r.gl_renderer, r.gl_version);
  r.build.version = "0.1.0";
  r.build.fingerprint = record::build_fingerprint(r.build);
  r.status = status;
  r.finished_at = "2026-12-01T00:00:00Z";
  return r;
}

// Timing of a coarse run: frame and technique samples, the shared passes
// the rest of each frame (three quarters G-buffer, a quarter shading).
inline record::TimingRecord coarse_timing(const std::vector<double>& frame,
                                          const std::vector<double>& technique) {
  record::TimingRecord t;
  t.warmup_frames = 1;
  t.timed_frames = static_cast<int>(frame.size());
  t.frame = record::Series::of(frame);
  t.technique = record::Series::of(technique);
  std::vector<double> gbuffer, shading;
  for (size_t i = 0; i < frame.size() && i < technique.size(); ++i) {
    gbuffer.push_back(0.75 * (frame[i] - technique[i]));
    shading.push_back(0.25 * (frame[i] - technique[i]));
  }
  t.shared["gbuffer"] = record::Series::of(gbuffer);
  t.shared["shading"] = record::Series::of(shading);
  return t;
}

// 20 frame times around 10 ms, spread ±`spread` ms in a fixed order
// (10 + spread × (7i mod 20 − 10) / 10): sorted, 10 − spread, 10 − 0.9
// spread, ..., 10 + 0.9 spread; so the median's interval, [x_(6), x_(15)],
// is [10 − 0.5 spread, 10 + 0.4 spread] around a median of 10 − 0.05 spread.
inline std::vector<double> spread_frames(double spread) {
  std::vector<double> out;
  for (int i = 0; i < 20; ++i) out.push_back(10.0 + spread * double((i * 7) % 20 - 10) / 10.0);
  return out;
}

// Per-pass detail as `run --pass-timing fine` adds it: `passes` in order,
// each with its samples.
inline void add_fine_timing(
    record::TimingRecord& t,
    const std::vector<std::pair<std::string, std::vector<double>>>& passes) {
  record::FineTiming fine;
  std::vector<double> sum;
  for (const auto& [name, samples] : passes) {
    fine.pass_order.push_back(name);
    fine.passes[name] = record::Series::of(samples);
    sum.resize(std::max(sum.size(), samples.size()));
    for (size_t i = 0; i < samples.size(); ++i) sum[i] += samples[i];
  }
  fine.frames = static_cast<int>(sum.size());
  fine.technique = record::Series::of(sum);
  std::vector<double> frame = sum;
  for (size_t i = 0; i < frame.size() && i < t.frame.samples.size(); ++i)
    frame[i] += t.frame.samples[i] - t.technique.samples[i];
  fine.frame = record::Series::of(frame);
  t.pass_timing = "fine";
  t.fine = std::move(fine);
}

}  // namespace sb::test
