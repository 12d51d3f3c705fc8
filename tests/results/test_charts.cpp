#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "../metrics/test_util.h"
#include "../record/sample_records.h"
#include "core/error.h"
#include "record/figures.h"
#include "results/charts.h"

namespace sb {

using core::InputError;
using record::BuiltScene;
using record::FineTiming;
using record::JobRecord;
using record::JobStatus;
using record::MetricsRecord;
using record::RegionStats;
using record::Series;
using record::TimingRecord;
using results::ChartFile;
using results::ChartOptions;
using results::charts_unavailable_reason;
using results::find_plot_script;
using results::write_charts;

namespace {

// A series of three frames whose median is `median` (p10 and p90 about 10 %
// and 20 % away).
Series timing(double median) { return Series::of({median * 0.875, median, median * 1.25}); }

struct Technique {
  std::string variant;
  double ms;    // technique time at 320x240 with 10k triangles
  double rmse;  // visibility.geometry.rmse (and every other region's)
  std::vector<std::string> passes;
  std::int64_t gpu_own_bytes;                          // technique.gpu_own_bytes
  std::map<std::string, std::int64_t> gpu_need_bytes;  // technique.gpu_need_bytes
  std::int64_t gpu_bytes() const {                     // technique.gpu_bytes, their sum
    std::int64_t sum = gpu_own_bytes;
    for (const auto& [need, bytes] : gpu_need_bytes) sum += bytes;
    return sum;
  }
};

// Four technique variants: none, shadow_map and accumulation are on the
// error-time front; pcf_box is slower than shadow_map and worse. In memory,
// accumulation's one 512² map (1 MiB) beats both 4 MiB: the error-memory
// front is none and accumulation. pcf_box holds nothing of its own here, but
// 4 MiB the harness holds for a need: drawn at its own 0 MiB, it would push
// none off the front.
const std::vector<Technique> kTechniques = {
    {"none", 0.1, 0.30, {"clear"}, 0, {}},
    {"shadow_map/size=1024", 5.0, 0.10, {"shadow_map", "lookup"}, 4 << 20, {}},
    {"pcf_box/k=3,size=1024",
     10.0,
     0.12,
     {"shadow_map", "lookup"},
     0,
     {{"edge_adjacency", 4 << 20}}},
    {"accumulation/samples=16", 190.0, 0.01, {"accumulate", "shadow_maps"}, 1 << 20, {}},
};

// The technique a chart's label names, or nullptr.
const Technique* technique_named(const nlohmann::json& label) {
  const auto t = std::find_if(kTechniques.begin(), kTechniques.end(),
                              [&](const Technique& k) { return k.variant == label; });
  return t == kTechniques.end() ? nullptr : &*t;
}

JobRecord record(const std::string& scene, int triangles, int w, int h, const Technique& t) {
  const double scale = (triangles / 10000.0) * (w * h / 76800.0);
  const double gbuffer = 9.0 * scale, shading = 1.0 * scale, tech = t.ms * scale;
  const std::string res = std::to_string(w) + "x" + std::to_string(h);
  JobRecord r = test::identity_record(scene, res, t.variant);
  r.scene.built = BuiltScene{};
  r.scene.built->triangles = triangles;
  r.technique.set_gpu_bytes(t.gpu_own_bytes, t.gpu_need_bytes);
  TimingRecord timing_record;
  timing_record.frame = timing(gbuffer + shading + tech);
  timing_record.technique = timing(tech);
  timing_record.shared = {{"gbuffer", timing(gbuffer)}, {"shading", timing(shading)}};
  FineTiming fine;
  fine.pass_order = t.passes;
  for (std::size_t i = 0; i < t.passes.size(); ++i)
    fine.passes[t.passes[i]] = timing(tech * (i == 0 ? 0.7 : 0.3));
  timing_record.pass_timing = "fine";
  timing_record.fine = fine;
  r.timing = timing_record;
  RegionStats stats;
  stats.rmse = t.rmse;
  stats.psnr = t.rmse > 0 ? -20 * std::log10(t.rmse) : 0.0;
  stats.ssim = 1.0 - t.rmse;
  stats.frac_over_005 = t.rmse / 2;
  r.metrics = MetricsRecord{{stats, stats, stats, stats}, {stats, stats, stats, stats}};
  return r;
}

std::vector<JobRecord> synthetic_records() {
  std::vector<JobRecord> out;
  for (const auto& [scene, triangles] :
       std::vector<std::pair<std::string, int>>{{"jeep/count=1", 10000}, {"jeep/count=4", 40000}})
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{320, 240}, {640, 480}})
      for (const auto& t : kTechniques) out.push_back(record(scene, triangles, w, h, t));
  // Not drawn: failed and skipped jobs.
  JobRecord failed =
      test::identity_record("jeep/count=1", "320x240", "broken_technique", JobStatus::Failed);
  failed.reason = "GL error";
  out.push_back(failed);
  out.push_back(
      test::identity_record("jeep/count=1", "320x240", "skipped_technique", JobStatus::Skipped));
  return out;
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A chart's data file (written beside its SVG).
nlohmann::json chart_data(const ChartFile& c) {
  return nlohmann::json::parse(
      read(std::filesystem::path(c.svg).replace_extension(".json").string()));
}

// How often `text` is an SVG <text> element's whole content.
int text_count(const std::string& svg, const std::string& text) {
  int n = 0;
  const std::string needle = ">" + text + "<";
  for (auto pos = svg.find(needle); pos != std::string::npos; pos = svg.find(needle, pos + 1)) ++n;
  return n;
}

#define SKIP_WITHOUT_MATPLOTLIB()                                        \
  if (const std::string why = charts_unavailable_reason(); !why.empty()) \
  GTEST_SKIP() << "charts cannot be drawn here: " << why

TEST(Charts, EveryChartIsWrittenWithItsSeries) {
  SKIP_WITHOUT_MATPLOTLIB();
  test::TempDir dir("charts");
  const auto charts = write_charts(synthetic_records(), dir.file("charts"), {});

  std::map<std::string, int> kinds;
  for (const auto& c : charts) ++kinds[c.kind];
  EXPECT_EQ(kinds["error_time"], 4);       // 2 scenes × 2 resolutions
  EXPECT_EQ(kinds["error_memory"], 4);     // likewise
  EXPECT_EQ(kinds["time_triangles"], 2);   // jeep at 2 resolutions
  EXPECT_EQ(kinds["error_triangles"], 2);  // likewise
  EXPECT_EQ(kinds["time_resolution"], 2);  // per scene
  EXPECT_EQ(kinds["passes"], 4);

  for (const auto& c : charts) {
    SCOPED_TRACE(c.kind + ": " + c.title);
    ASSERT_TRUE(std::filesystem::exists(c.svg)) << c.svg;
    ASSERT_TRUE(std::filesystem::exists(c.png)) << c.png;
    EXPECT_GT(std::filesystem::file_size(c.svg), 1000u);
    const std::string png = read(c.png);
    ASSERT_GT(png.size(), 1000u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << c.png;
    const std::string svg = read(c.svg);
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_GE(text_count(svg, c.title), 1) << "title missing";
    ASSERT_EQ(c.series.size(), kTechniques.size());
    for (const auto& t : kTechniques) {
      EXPECT_NE(std::find(c.series.begin(), c.series.end(), t.variant), c.series.end());
      EXPECT_GE(text_count(svg, t.variant), 1) << t.variant << " missing from " << c.svg;
    }
    EXPECT_EQ(svg.find("broken_technique"), std::string::npos);
    EXPECT_EQ(svg.find("skipped_technique"), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(c.svg).replace_extension(".json")));
    if (c.kind == "error_triangles") {
      // Each technique's error at each triangle count, as its records hold it.
      const auto data = chart_data(c);
      for (const auto& s : data["series"]) {
        const Technique* t = technique_named(s["label"]);
        ASSERT_NE(t, nullptr);
        ASSERT_EQ(s["points"].size(), 2u);
        EXPECT_EQ(s["points"][0]["x"], 10000.0);
        EXPECT_EQ(s["points"][1]["x"], 40000.0);
        for (const auto& p : s["points"]) EXPECT_EQ(p["y"].get<double>(), t->rmse);
      }
    }
    if (c.kind == "error_time") {
      EXPECT_NE(svg.find("visibility.geometry.rmse"), std::string::npos) << "axis names the metric";
      const std::vector<std::string> front = {"none", "shadow_map/size=1024",
                                              "accumulation/samples=16"};
      EXPECT_EQ(c.pareto, front);
      // Front points are labelled beside the point as well as in the legend.
      for (const auto& name : front) EXPECT_EQ(text_count(svg, name), 2) << name;
      EXPECT_EQ(text_count(svg, "pcf_box/k=3,size=1024"), 1);
      EXPECT_EQ(text_count(svg, "Pareto front"), 1);
    }
    if (c.kind == "error_memory") {
      EXPECT_NE(svg.find("GPU memory: the technique"), std::string::npos) << "axis names the cost";
      EXPECT_EQ(c.pareto, (std::vector<std::string>{"none", "accumulation/samples=16"}));
      // Each point at its technique's MiB, its own and its needs', as its record holds them.
      const auto data = chart_data(c);
      for (const auto& p : data["points"]) {
        const Technique* t = technique_named(p["label"]);
        ASSERT_NE(t, nullptr);
        EXPECT_EQ(p["x"].get<double>(), static_cast<double>(t->gpu_bytes()) / (1 << 20));
        EXPECT_EQ(p["y"].get<double>(), t->rmse);
      }
      EXPECT_FALSE(data["xlog"].get<bool>()) << "a log axis cannot show none's 0 MiB";
    }
    if (c.kind == "passes") {
      for (const char* pass : {"gbuffer (shared)", "shading (shared)", "shadow_map", "lookup",
                               "accumulate", "shadow_maps", "clear"})
        EXPECT_EQ(text_count(svg, pass), 1) << pass;
    }
  }
  // Stable, file-system-safe names.
  EXPECT_EQ(charts.front().svg, dir.file("charts") + "/error_time__jeep--count=1__320x240.svg");
}

TEST(Charts, RecordsWithoutTheGpuMemoryTotalGetNoMemoryChart) {
  SKIP_WITHOUT_MATPLOTLIB();
  // As written before technique.gpu_bytes, and before it counted the needs
  // (gpu_bytes alone, the technique's own: not a total to draw).
  for (const bool own_only : {false, true}) {
    SCOPED_TRACE(own_only ? "gpu_bytes without its parts" : "no gpu_bytes");
    test::TempDir dir(own_only ? "charts_own_memory_only" : "charts_no_memory");
    std::vector<JobRecord> records;
    for (JobRecord r : synthetic_records())
      if (r.scene_variant == "jeep/count=1" && r.resolution == "320x240") {
        if (!own_only) r.technique.gpu_bytes.reset();
        r.technique.gpu_own_bytes.reset();
        r.technique.gpu_need_bytes.reset();
        records.push_back(r);
      }
    const auto charts = write_charts(records, dir.path().string(), {});
    std::vector<std::string> kinds(charts.size());
    std::transform(charts.begin(), charts.end(), kinds.begin(),
                   [](const ChartFile& c) { return c.kind; });
    EXPECT_EQ(kinds, (std::vector<std::string>{"error_time", "passes"}));
  }
}

TEST(Charts, HigherIsBetterMetricsFlipTheFront) {
  SKIP_WITHOUT_MATPLOTLIB();
  test::TempDir dir("charts_ssim");
  ChartOptions o;
  o.error_metric = "shaded.all.ssim";
  std::vector<JobRecord> records;  // one scene at one resolution: quicker
  for (const JobRecord& r : synthetic_records())
    if (r.scene_variant == "jeep/count=1" && r.resolution == "320x240") records.push_back(r);
  const auto charts = write_charts(records, dir.path().string(), o);
  ASSERT_EQ(charts.size(), 3u);  // error_time, error_memory and passes
  EXPECT_EQ(charts.front().kind, "error_time");
  EXPECT_EQ(charts.front().pareto,
            (std::vector<std::string>{"none", "shadow_map/size=1024", "accumulation/samples=16"}));
  EXPECT_NE(read(charts.front().svg).find("shaded.all.ssim (higher is better)"), std::string::npos);
}

// Coarse pass timing (the default) records no passes: each bar still shows
// the technique's time, as one segment.
TEST(Charts, CoarseRunsShowTheTechniqueAsOneSegment) {
  SKIP_WITHOUT_MATPLOTLIB();
  test::TempDir dir("charts_coarse");
  std::vector<JobRecord> records;
  for (JobRecord r : synthetic_records())
    if (r.scene_variant == "jeep/count=1" && r.resolution == "320x240" && r.timing) {
      r.timing->fine.reset();
      r.timing->pass_timing = "coarse";
      records.push_back(r);
    }
  const auto charts = write_charts(records, dir.path().string(), ChartOptions{});
  ASSERT_EQ(charts.size(), 3u);  // error_time, error_memory and passes
  const std::string svg = read(charts.back().svg);
  EXPECT_EQ(charts.back().kind, "passes");
  EXPECT_EQ(text_count(svg, "technique (all passes)"), 1);
  EXPECT_EQ(text_count(svg, "lookup"), 0);
}

TEST(Charts, UnknownMetricIsAnInputErrorNamingIt) {
  test::TempDir dir("charts_bad");
  ChartOptions o;
  o.error_metric = "visibility.all.nope";
  try {
    write_charts(synthetic_records(), dir.path().string(), o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("visibility.all.nope"), std::string::npos) << e.what();
    // What a path may be, from the catalogue (record/figures.h).
    EXPECT_NE(std::string(e.what()).find(record::metric_path_syntax()), std::string::npos)
        << e.what();
  }
  o.error_metric = "visibility";  // an object, not a number
  EXPECT_THROW(write_charts(synthetic_records(), dir.path().string(), o), InputError);
}

// A stand-in plot_charts.py found through $SHADOWBENCH_SHARE_DIR.
class FakeScript {
 public:
  FakeScript(const test::TempDir& dir, const std::string& body) {
    std::ofstream(dir.file("plot_charts.py")) << body;
    ::setenv("SHADOWBENCH_SHARE_DIR", dir.path().c_str(), 1);
  }
  ~FakeScript() { ::unsetenv("SHADOWBENCH_SHARE_DIR"); }
};

TEST(Charts, ScriptFailureCarriesItsStderr) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  test::TempDir dir("charts_fail");
  FakeScript script(dir, "import sys\nprint('boom: no such axis', file=sys.stderr)\nsys.exit(1)\n");
  EXPECT_EQ(find_plot_script(), dir.file("plot_charts.py"));
  try {
    write_charts(synthetic_records(), dir.file("out"), {});
    FAIL() << "expected runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("boom: no such axis"), std::string::npos) << e.what();
  }
}

TEST(Charts, MissingMatplotlibSaysWhatToInstall) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  test::TempDir dir("charts_nompl");
  FakeScript script(dir, "import sys\nsys.exit(3)\n");  // plot_charts.py's "import failed"
  try {
    write_charts(synthetic_records(), dir.file("out"), {});
    FAIL() << "expected runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install python3-matplotlib"), std::string::npos)
        << e.what();
  }
}

TEST(Charts, NoOkRecordsNoCharts) {
  test::TempDir dir("charts_none");
  std::vector<JobRecord> records = synthetic_records();
  for (auto& r : records) r.status = JobStatus::Failed;
  EXPECT_TRUE(write_charts(records, dir.path().string(), {}).empty());
}

}  // namespace
}  // namespace sb
