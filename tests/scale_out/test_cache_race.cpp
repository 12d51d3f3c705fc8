// Two runs sharing --cache-dir, started together on one reference: it is
// computed once, by whichever takes its key's lock first, and read by the
// other; the cache holds one whole file and no temporary one.
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "scale_out_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

TEST(CacheRace, TwoProcessesRacingOnOneKeyComputeItOnce) {
  const auto dir = test_folder();
  // A reference that takes a while (320×240 at 1024 spp), so both runs are
  // inside it at once.
  const json config = {{"name", "race"},
                       {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 3}}}}}},
                       {"techniques", {"none"}},
                       {"resolutions", {"320x240"}},
                       {"frames", {{"warmup", 0}, {"timed", 1}, {"control", nullptr}}},
                       {"reference", {{"spp", 1024}}}};
  std::ofstream(dir / "race.json") << config.dump();
  const std::string args = "run " + (dir / "race.json").string() + " --no-images --quiet" +
                           " --cache-dir " + (dir / "cache").string() + " --out ";
  CliRun a, b;
  std::thread ta([&] { a = run_shadowbench(args + (dir / "a").string()); });
  std::thread tb([&] { b = run_shadowbench(args + (dir / "b").string()); });
  ta.join();
  tb.join();
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const json ra = jsonl_records(dir / "a").at(0)["reference"];
  const json rb = jsonl_records(dir / "b").at(0)["reference"];
  EXPECT_EQ(ra["cache_key"], rb["cache_key"]);
  EXPECT_NE(ra["from_cache"], rb["from_cache"]) << "computed twice, or by neither";
  EXPECT_EQ(ra["mean_std_error"], rb["mean_std_error"]);
  EXPECT_EQ(ra["penumbra_rms_std_error"], rb["penumbra_rms_std_error"]);
  size_t whole = 0;
  for (const auto& e : fs::directory_iterator(dir / "cache")) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    whole += e.path().extension() == ".sbref" ? 1 : 0;
  }
  EXPECT_EQ(whole, 1u);
}

}  // namespace
}  // namespace sb::test
