// `compare` on real runs and the reference each names:
// a run without the reference cache and one with it name the same
// reference (record["reference"]["cache_key"] is written either way), so
// their errors compare; a run against a reference of other spp is refused
// on errors (exit 2, naming spp and its values), compared with
// --allow-reference-change, and passes on times alone with --metric none.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../config/cli_runner.h"
#include "e2e_util.h"
#include "store/results_store.h"

namespace sb::test {

using store::read_job_records;

namespace {

namespace fs = std::filesystem;

std::string write_spp_config(const fs::path& dir, int spp) {
  const nlohmann::json config = {{"name", "refs"},
                                 {"scenes", {small_scene(2.0)}},
                                 {"techniques", {"none"}},
                                 {"resolutions", {{64, 48}}},
                                 {"frames", {{"warmup", 1}, {"timed", 6}}},
                                 {"reference", {{"spp", spp}}}};
  const fs::path path = dir / ("refs" + std::to_string(spp) + ".json");
  std::ofstream(path) << config.dump(2);
  return path.string();
}

TEST(CompareReferences, RunsNameTheirReferenceAndCompareOnlyAgainstTheSame) {
  const fs::path dir = fresh_test_folder("compare_references_");
  const std::string c16 = write_spp_config(dir, 16), c64 = write_spp_config(dir, 64);
  const std::string plain = (dir / "plain").string(), cached = (dir / "cached").string(),
                    other = (dir / "other").string(), cache = (dir / "cache").string();
  ASSERT_EQ(run_cli("run " + c16 + " --out " + plain + " --no-cache --no-images --quiet").exit_code,
            0);
  ASSERT_EQ(
      run_cli("run " + c16 + " --out " + cached + " --cache-dir " + cache + " --no-images --quiet")
          .exit_code,
      0);
  ASSERT_EQ(run_cli("run " + c64 + " --out " + other + " --no-cache --no-images --quiet").exit_code,
            0);
  const auto a = read_job_records(plain), b = read_job_records(cached);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  ASSERT_TRUE(a[0].reference && b[0].reference);
  EXPECT_EQ(a[0].reference->cache_key.size(), 16u);  // also without the cache
  EXPECT_EQ(a[0].reference->cache_key, b[0].reference->cache_key);

  // --timing none: this test is about the errors.
  auto r = run_cli("compare " + plain + " " + cached + " --timing none");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("reference: differs"), std::string::npos) << r.output;

  r = run_cli("compare " + plain + " " + other + " --timing none");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("spp: \"16\" vs \"64\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cache_key: \""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the error of 1 job(s) was not compared"), std::string::npos) << r.output;
  r = run_cli("compare " + plain + " " + other + " --timing none --allow-reference-change");
  EXPECT_NE(r.exit_code, 2) << r.output;  // 0, or 4 if 16 against 64 spp moved the error
  EXPECT_NE(r.output.find("errors compared anyway"), std::string::npos) << r.output;
  r = run_cli("compare " + plain + " " + other + " --metric none --time-threshold 100");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

}  // namespace
}  // namespace sb::test
