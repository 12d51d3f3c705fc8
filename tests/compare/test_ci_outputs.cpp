// The CI outputs: Google Benchmark JSON (read by Debian's compare.py from
// libbenchmark-tools) and Bencher Metric Format JSON.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "results/bencher_json.h"
#include "results/benchmark_json.h"
#include "synthetic_run.h"

namespace {

using nlohmann::json;
using sb::test::make_record;
using sb::test::noisy_samples;
namespace fs = std::filesystem;

std::vector<sb::record::JobRecord> synthetic_records(double slowdown, uint32_t seed) {
  std::vector<sb::record::JobRecord> rs;
  rs.push_back(make_record("grid__320x240__shadow_map--size=1024",
                           noisy_samples(20.0 * slowdown, 0.03, 15, seed), 0.10, 0.27));
  rs.push_back(make_record("grid__320x240__pcf_box--k=3+size=1024",
                           noisy_samples(25.0 * slowdown, 0.03, 15, seed + 1), 0.055, 0.15));
  sb::record::JobRecord skipped =
      sb::test::identity_record("grid", "320x240", "shadow_volume", sb::record::JobStatus::Skipped);
  skipped.reason = "casters are not closed";
  rs.push_back(skipped);
  return rs;
}

std::vector<const json*> named(const json& doc, const std::string& name) {
  std::vector<const json*> out;
  for (const auto& b : doc["benchmarks"])
    if (b["name"] == name) out.push_back(&b);
  return out;
}

TEST(BenchmarkJson, OneBenchmarkPerJobAndPassWithRepetitions) {
  const auto records = synthetic_records(1.0, 1);
  const json doc = sb::results::make_benchmark_json(records, sb::results::benchmark_context());
  const json& ctx = doc["context"];
  for (const char* key : {"date", "host_name", "num_cpus", "mhz_per_cpu", "caches",
                          "library_build_type", "json_schema_version"})
    EXPECT_TRUE(ctx.contains(key)) << key;
  EXPECT_TRUE(ctx["caches"].is_array());
  EXPECT_EQ(ctx["json_schema_version"], 1);
  EXPECT_EQ(ctx["shadowbench_run_id"], "synthetic");

  // 2 ok jobs × (frame + 2 passes) × (15 repetitions + 4 aggregates).
  EXPECT_EQ(doc["benchmarks"].size(), 2u * 3u * 19u);
  const std::string frame = "grid__320x240__shadow_map--size=1024/frame";
  const auto reps = named(doc, frame);
  ASSERT_EQ(reps.size(), 15u);
  const auto& samples = records[0].timing->frame.samples;
  for (size_t i = 0; i < reps.size(); ++i) {
    const json& e = *reps[i];
    EXPECT_EQ(e["run_name"], frame);
    EXPECT_EQ(e["run_type"], "iteration");
    EXPECT_EQ(e["repetitions"], 15);
    EXPECT_EQ(e["repetition_index"], i);
    EXPECT_EQ(e["threads"], 1);
    EXPECT_EQ(e["iterations"], 1);
    EXPECT_EQ(e["time_unit"], "ms");
    EXPECT_DOUBLE_EQ(e["real_time"].get<double>(), samples[i]);
    EXPECT_DOUBLE_EQ(e["cpu_time"].get<double>(), samples[i]);
  }
  const auto median = named(doc, frame + "_median");
  ASSERT_EQ(median.size(), 1u);
  EXPECT_EQ((*median[0])["run_type"], "aggregate");
  EXPECT_EQ((*median[0])["aggregate_name"], "median");
  EXPECT_EQ((*median[0])["run_name"], frame);
  EXPECT_DOUBLE_EQ((*median[0])["real_time"].get<double>(), records[0].timing->frame.median);
  EXPECT_EQ((*named(doc, frame + "_cv")[0])["aggregate_unit"], "percentage");
  EXPECT_EQ(named(doc, "grid__320x240__shadow_map--size=1024/pass:depth").size(), 15u);
  EXPECT_EQ(named(doc, "grid__320x240__pcf_box--k=3+size=1024/pass:lookup").size(), 15u);
  for (const auto& b : doc["benchmarks"])
    EXPECT_EQ(b["name"].get<std::string>().find("shadow_volume"), std::string::npos);
}

TEST(BenchmarkJson, WrittenAtomically) {
  const auto dir = sb::test::temp_dir("atomic");
  const std::string path = (dir / "bench.json").string();
  sb::results::write_benchmark_json(path, synthetic_records(1.0, 1));
  std::ifstream in(path);
  const json doc = json::parse(in);
  EXPECT_EQ(doc["benchmarks"].size(), 114u);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename(), "bench.json") << "no temporary file may stay behind";
}

int run(const std::string& cmd, std::string& out) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  std::array<char, 512> buf{};
  while (fgets(buf.data(), int(buf.size()), pipe) != nullptr) out += buf.data();
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Debian's compare.py (libbenchmark-tools 1.7.1, which needs python3-scipy)
// reads our JSON, pairs the repetitions by name and runs its U test.
TEST(BenchmarkJson, AcceptedByDebiansComparePy) {
  const char* compare_py = "/usr/share/benchmark/compare.py";
  if (!fs::exists(compare_py))
    GTEST_SKIP() << compare_py << " is absent: install libbenchmark-tools "
                 << "(scripts/install-deps.sh --test)";
  std::string probe;
  if (run("/usr/bin/python3 -c 'import scipy.stats'", probe) != 0)
    GTEST_SKIP() << "python3 cannot import scipy.stats: install python3-scipy "
                 << "(scripts/install-deps.sh --test)";
  const auto dir = sb::test::temp_dir("compare_py");
  const std::string a = (dir / "A.json").string(), b = (dir / "B.json").string();
  sb::results::write_benchmark_json(a, synthetic_records(1.0, 1));
  sb::results::write_benchmark_json(b, synthetic_records(1.3, 7));
  std::string out;
  const int code = run(
      std::string("/usr/bin/python3 ") + compare_py + " --no-color benchmarks " + a + " " + b, out);
  ASSERT_EQ(code, 0) << out;
  for (const char* name : {"grid__320x240__shadow_map--size=1024/frame",
                           "grid__320x240__shadow_map--size=1024/pass:depth",
                           "grid__320x240__pcf_box--k=3+size=1024/pass:lookup",
                           "grid__320x240__pcf_box--k=3+size=1024/frame_median",
                           "grid__320x240__pcf_box--k=3+size=1024/frame_pvalue", "OVERALL_GEOMEAN"})
    EXPECT_NE(out.find(name), std::string::npos) << name << "\n" << out;
  // The 30 % slowdown shows as about +0.30 on the median line.
  const size_t line = out.find("grid__320x240__shadow_map--size=1024/frame_median");
  ASSERT_NE(line, std::string::npos);
  const std::string median_line = out.substr(line, out.find('\n', line) - line);
  const size_t sign = median_line.find_first_of("+-", median_line.find(' '));
  ASSERT_NE(sign, std::string::npos) << median_line;
  EXPECT_NEAR(std::stod(median_line.substr(sign)), 0.30, 0.06) << median_line;
}

TEST(BencherJson, FollowsTheMetricFormat) {
  const auto records = synthetic_records(1.0, 1);
  const json doc = sb::results::make_bencher_json(records);
  ASSERT_EQ(doc.size(), 2u);  // the skipped job has no measures
  const json& b = doc["grid__320x240__shadow_map--size=1024"];
  const sb::record::Series& frame = records[0].timing->frame;
  // Bencher's built-in latency measure is in nanoseconds.
  EXPECT_DOUBLE_EQ(b["latency"]["value"].get<double>(), frame.median * 1e6);
  EXPECT_DOUBLE_EQ(b["latency"]["lower_value"].get<double>(), frame.p10 * 1e6);
  EXPECT_DOUBLE_EQ(b["latency"]["upper_value"].get<double>(), frame.p90 * 1e6);
  EXPECT_DOUBLE_EQ(b["rmse"]["value"].get<double>(), 0.10);
  EXPECT_DOUBLE_EQ(b["penumbra-rmse"]["value"].get<double>(), 0.27);
  // The BMF schema: every measure an object with a numeric "value" and at
  // most value, lower_value, upper_value.
  for (const auto& [name, measures] : doc.items())
    for (const auto& [slug, m] : measures.items()) {
      EXPECT_LE(slug.size(), 64u);
      ASSERT_TRUE(m.contains("value")) << name << " " << slug;
      for (const auto& [k, v] : m.items()) {
        EXPECT_TRUE(k == "value" || k == "lower_value" || k == "upper_value") << k;
        EXPECT_TRUE(v.is_number()) << k;
      }
    }
  // Non-finite errors have no JSON number: the measure is left out.
  auto with_nan = records;
  with_nan[0].metrics->visibility.all.rmse = std::nan("");
  EXPECT_FALSE(
      sb::results::make_bencher_json(with_nan)["grid__320x240__shadow_map--size=1024"].contains(
          "rmse"));
}

}  // namespace
