#pragma once
// A synthetic run directory for the HTML report tests: records built as the
// runner builds them (JobRecord; two scene/resolution groups; ok, skipped and failed jobs; a
// reason with <&>"' in it; file names with '=', '+' and ','), tiny PNGs for
// their images, and one chart (SVG + PNG) in the report folder.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../common/text.h"
#include "../record/sample_records.h"
#include "core/image.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "metrics/regions.h"
#include "results/html_report.h"

namespace sb::test {

inline constexpr const char* kNastyReason = "GL error <GL_INVALID_ENUM> & \"bad\" 'enum'";

struct SyntheticRun {
  std::filesystem::path run_dir, out_dir;
  std::vector<record::JobRecord> records;
  std::vector<results::ReportChart> charts;
};

// A small image with a gradient and a disc, so a screenshot of it is not flat.
inline core::ImageF synthetic_image(int w, int h, float shift) {
  const float fw = static_cast<float>(w), fh = static_cast<float>(h);
  core::ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float fx = static_cast<float>(x), fy = static_cast<float>(y);
      const float dx = fx - fw * (0.3f + shift), dy = fy - fh * 0.5f;
      const float v = dx * dx + dy * dy < fh * fh / 9.0f ? 0.15f : 0.4f + 0.5f * fx / fw;
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = v * (0.8f + 0.1f * static_cast<float>(c));
    }
  }
  return img;
}

// A one-channel V in [0.05, 0.53] that differs at every pixel (a slope in x
// and y, steeper in x by `shift`, a darker disc moved by it), so a value read
// from it names its pixel, and jobs differ from the reference by up to 0.08
// (shift <= 0.15); the reference's standard error is 0.01 + 0.001 x.
inline core::ImageF synthetic_visibility(int w, int h, float shift) {
  core::ImageF img(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float fx = static_cast<float>(x), fy = static_cast<float>(y);
      const float dx = fx - static_cast<float>(w) * (0.3f + shift),
                  dy = fy - static_cast<float>(h) * 0.5f;
      const float disc = dx * dx + dy * dy < static_cast<float>(h * h) / 9.0f ? -0.05f : 0.0f;
      img.at(x, y, 0) = 0.1f + (0.3f + 0.5f * shift) * fx / static_cast<float>(w) +
                        0.05f * fy / static_cast<float>(h) + disc;
    }
  return img;
}

// Writes the run into root/run; the report goes to `out_dir` (root/report
// unless given).
inline SyntheticRun make_synthetic_run(const std::filesystem::path& root,
                                       const std::filesystem::path& out_dir = {}) {
  namespace fs = std::filesystem;
  SyntheticRun run;
  run.run_dir = root / "run";
  run.out_dir = out_dir.empty() ? root / "report" : out_dir;
  fs::create_directories(run.run_dir);
  fs::create_directories(run.out_dir / "charts");
  const float full_scale = 0.25f;
  struct Job {
    const char* technique;
    record::JobStatus status;
    std::string reason;
    double frame_ms;  // in an order that text sorting would get wrong
  };
  const Job jobs[] = {
      {"none", record::JobStatus::Ok, "", 2.5},
      {"shadow_map/size=1024", record::JobStatus::Ok, "", 12.0},
      {"pcf_box/k=3,size=1024", record::JobStatus::Ok, "", 9.0},
      {"shadow_volume/mode=zpass", record::JobStatus::Skipped, "casters are not closed", 0.0},
      {"vsm/k=9,prefilter=gauss", record::JobStatus::Failed, kNastyReason, 120.0}};
  const std::pair<int, int> sizes[] = {{64, 48}, {96, 72}};
  for (const auto& [w, h] : sizes) {
    const std::string res = std::to_string(w) + "x" + std::to_string(h);
    const std::string scene = "plates/layout=edge";
    const std::string ref_rel = "reference/plates--layout=edge__" + res;
    fs::create_directories(run.run_dir / ref_rel);
    const core::ImageF ref = synthetic_image(w, h, 0.0f);
    metrics::io::write_png((run.run_dir / ref_rel / "shaded.png").string(), ref);
    const core::ImageF ref_v = synthetic_visibility(w, h, 0.0f);
    metrics::io::write_exr((run.run_dir / ref_rel / "visibility.exr").string(), ref_v);
    core::ImageF sigma(w, h, 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) sigma.at(x, y, 0) = 0.01f + 0.001f * static_cast<float>(x);
    metrics::io::write_exr((run.run_dir / ref_rel / "std_error.exr").string(), sigma);
    // The measured pixels (region "all"): all but the last 4 columns.
    std::vector<uint8_t> measured(static_cast<size_t>(w * h));
    for (size_t p = 0; p < measured.size(); ++p)
      measured[p] = p % static_cast<size_t>(w) < size_t(w - 4);
    metrics::io::write_mask_png((run.run_dir / ref_rel / "mask_all.png").string(), measured, w, h);
    float shift = 0.0f;
    for (const auto& j : jobs) {
      std::string safe = j.technique;
      for (char& c : safe) c = c == '/' ? '-' : c == ',' ? '+' : c;
      record::JobRecord r = identity_record(scene, res, j.technique, j.status);
      r.job_id = "plates--layout=edge__" + res;
      r.job_id += "__" + safe;
      r.gl_renderer = "llvmpipe <test>";
      r.reference = record::ReferenceRecord{};
      r.reference->method = "embree_stratified_packet16";
      r.reference->spp = 256;
      if (!j.reason.empty()) r.reason = j.reason;
      if (j.status != record::JobStatus::Skipped) {
        shift += 0.05f;
        const std::string rel = "jobs/" + r.job_id;
        fs::create_directories(run.run_dir / rel);
        const core::ImageF test = synthetic_image(w, h, shift);
        metrics::io::write_png((run.run_dir / rel / "shaded.png").string(), test);
        // The error heat map as the runner makes it: of V, over the measured pixels.
        const core::ImageF v = synthetic_visibility(w, h, shift);
        metrics::io::write_png(
            (run.run_dir / rel / "error.png").string(),
            metrics::error_heatmap(metrics::with_unmeasured_from(v, ref_v, measured), ref_v,
                                   full_scale));
        metrics::io::write_exr((run.run_dir / rel / "visibility.exr").string(), v);
        r.images.visibility = rel + "/visibility.exr";
        r.images.shaded = rel + "/shaded.png";
        r.images.error_heatmap = rel + "/error.png";
        r.images.error_heatmap_full_scale = full_scale;
        r.images.reference_shaded = ref_rel + "/shaded.png";
        r.images.reference_visibility = ref_rel + "/visibility.exr";
        r.images.reference_std_error = ref_rel + "/std_error.exr";
        r.images.masks["all"] = ref_rel + "/mask_all.png";
        r.timing = coarse_timing({j.frame_ms}, {0.5 + shift * 10.0});
        record::MetricsRecord m;
        m.visibility.all.rmse = 0.2 - shift;
        m.visibility.all.mae = 0.1;
        m.visibility.all.max_error = 1.0;
        m.visibility.all.psnr = std::numeric_limits<double>::infinity();
        m.visibility.all.ssim = 0.9;
        m.visibility.all.frac_over_005 = 0.01;
        m.visibility.penumbra.rmse = 0.3 - shift;
        m.visibility.geometry = m.visibility.all;  // no sky in the figures
        r.metrics = m;
      }
      run.records.push_back(r);
    }
  }
  // A chart as the caller makes it: files in the report folder.
  const std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"200\" "
      "viewBox=\"0 0 400 200\"><rect width=\"400\" height=\"200\" fill=\"#fff\"/>"
      "<polyline points=\"20,180 120,90 220,120 380,20\" fill=\"none\" stroke=\"#c33\" "
      "stroke-width=\"3\"/></svg>\n";
  {
    std::FILE* f = std::fopen((run.out_dir / "charts" / "error_vs_time.svg").c_str(), "wb");
    std::fputs(svg.c_str(), f);
    std::fclose(f);
  }
  metrics::io::write_png((run.out_dir / "charts" / "error_vs_time.png").string(),
                         synthetic_image(40, 20, 0.1f));
  run.charts.push_back(
      {"Error against frame time <all>", "charts/error_vs_time.svg", "charts/error_vs_time.png"});
  return run;
}

// The whole of a file (empty when it cannot be read).
// The text between each `open` and the next `close` (no std::regex: GCC 12
// warns inside it under the sanitizers).
inline std::vector<std::string> between(const std::string& text, const std::string& open,
                                        const std::string& close) {
  std::vector<std::string> out;
  for (size_t p = text.find(open); p != std::string::npos; p = text.find(open, p)) {
    p += open.size();
    const size_t end = text.find(close, p);
    if (end == std::string::npos) break;
    out.push_back(text.substr(p, end - p));
    p = end;
  }
  return out;
}

inline void write_synthetic_report(const SyntheticRun& run) {
  results::write_html_report(run.records, run.run_dir.string(), run.out_dir.string(), run.charts,
                             "synthetic <report> & co");
}

}  // namespace sb::test
