#pragma once
// Comparison charts of a run's records, drawn by matplotlib (Debian's
// python3-matplotlib) as SVG and PNG. The data are prepared here; one JSON
// data file per chart (<name>.json) goes into the output folder, and
// plot_charts.py draws all of them in one python3 process.
//
// Charts (only records with status "ok"; times are the frame's median, with
// p10–p90 error bars):
//  - error_time:      error against frame time, per (scene variant,
//                     resolution); the Pareto front as a step line, labelled;
//                     the timing control (results/control_baseline.h) is
//                     drawn hollow and grey, "(control)" in the legend, and
//                     is never on the front;
//  - time_triangles:  frame time against scene.triangles, per (scene type,
//                     resolution), when the type has >= 2 triangle counts;
//  - error_triangles: the error metric against scene.triangles, likewise;
//  - time_resolution: frame time against width×height, per scene variant,
//                     when it ran at >= 2 resolutions;
//  - passes:          per-pass stacked bars per (scene variant, resolution):
//                     timing.passes.<name>.median_ms in pass_order, over the
//                     shared G-buffer and shading passes in grey.
#include <string>
#include <vector>

#include "record/figures.h"
#include "record/job_record.h"

namespace sb::results {

struct ChartOptions {
  // A dotted path into record["metrics"] (record/metrics_record.h, MetricPath):
  // <visibility|shaded>.<region>.<key>, e.g. visibility.penumbra.rmse,
  // shaded.geometry.ssim, visibility.all.frac_over_0.05. The default region,
  // geometry, does not change with framing (docs/results.md, "Regions").
  // For psnr and ssim higher is better, and the Pareto front follows that.
  std::string error_metric = record::kDefaultErrorMetric;
  // "default", or "paper": each chart also as vector PDF, 3.3 in wide (a
  // two-column paper's column), 8 pt Computer Modern (matplotlib's mathtext
  // fonts), no title (the caption says it), the legend below the axes.
  std::string style = "default";
};

struct ChartFile {
  std::string kind;   // error_time, time_triangles, error_triangles, time_resolution, passes
  std::string title;  // as drawn above the chart
  std::string svg;    // paths of the written files (out_dir/<name>.svg, .png)
  std::string png;
  std::string pdf;                  // style "paper" only, else empty
  std::vector<std::string> series;  // technique variants drawn (legend or bar labels)
  std::vector<std::string> pareto;  // error_time only: the labelled front, by time (no control)
};

// Writes every chart the records support into out_dir (created if missing)
// and returns them, in a stable order. Throws InputError for an unknown
// error metric (naming it), std::runtime_error when python3 or matplotlib is
// missing (saying what to install) or when the plotting script fails (with
// its stderr). No ok records: no charts, and python is not run.
std::vector<ChartFile> write_charts(const std::vector<record::JobRecord>& records,
                                    const std::string& out_dir, const ChartOptions& options = {});

// Draws charts prepared elsewhere (the history report's): each file is one
// chart's JSON data as plot_charts.py reads it (its "kind", and the "svg" and
// "png" it writes), all in one python3 process. Throws as write_charts does.
void draw_chart_data(const std::vector<std::string>& data_files);

// Empty if /usr/bin/python3 can import matplotlib, else why not (and what to
// install). Runs python3 once.
std::string charts_unavailable_reason();

// The plotting script found as write_charts() looks for it: in data_dirs()
// (core/install_layout.h: $SHADOWBENCH_SHARE_DIR, the build tree's or the
// installed share folder), then in the source tree.
std::string find_plot_script();

}  // namespace sb::results
