// Unequal shadow-map sizes among compared techniques (config/map_sizes.h):
// a warning naming both sizes and the size's JSON pointer; none for equal
// sizes, a swept size or an entry marked "own_map_size"; validate and plan
// print it (run loads its config through the same function,
// cli::load_checked_experiment); no shipped config has one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../common/text.h"
#include "cli_runner.h"
#include "config/map_sizes.h"
#include "core/error.h"
#include "plugin/registry.h"

namespace sb::test {

using config::Experiment;
using config::ExperimentLimits;
using config::load_experiment;
using config::parse_experiment;
using config::unequal_map_size_warnings;
using core::InputError;
using plugin::Registry;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

json config_with(const json& techniques) {
  return {{"name", "map_sizes"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 1}}}}}},
          {"techniques", techniques},
          {"resolutions", {{16, 12}}},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 1}}}};
}

const Registry& shipped() {
  static const Registry r = [] {
    Registry loaded;
    loaded.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    return loaded;
  }();
  return r;
}

std::vector<std::string> warnings_for(const json& techniques) {
  return unequal_map_size_warnings(
      parse_experiment(config_with(techniques), "sizes.json", shipped()));
}

TEST(MapSizes, A1024MapBesideA2048MapWarnsNamingBoth) {
  const std::vector<std::string> w =
      warnings_for({{{"name", "shadow_map"}, {"params", {{"size", 2048}}}},
                    {{"name", "penumbra_maps"}, {"params", {{"size", 1024}}}},
                    {{"name", "pcss"}, {"params", {{"size", 2048}}}}});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(has(w[0], "sizes.json: at /techniques/1/params/size:")) << w[0];
  EXPECT_TRUE(has(w[0], "penumbra_maps/size=1024 renders a 1024-texel map (size)")) << w[0];
  EXPECT_TRUE(has(w[0], "2 others (shadow_map/size=2048 among them) render 2048")) << w[0];
}

TEST(MapSizes, EqualSizesDoNotWarn) {
  EXPECT_EQ(warnings_for({{{"name", "shadow_map"}, {"params", {{"size", 1024}}}},
                          {{"name", "penumbra_maps"}, {"params", {{"size", 1024}}}},
                          "plateaus",
                          "none"}),
            std::vector<std::string>{});
}

// Defaults count: pcss's is 2048, accumulation's 1024; the pointer is then
// the entry's, since no size was written.
TEST(MapSizes, DefaultSizesCountAndPointAtTheEntry) {
  const std::vector<std::string> w = warnings_for({"pcss", "accumulation"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(has(w[0], "sizes.json: at /techniques/1: technique accumulation renders a 1024"))
      << w[0];
  EXPECT_TRUE(has(w[0], "pcss render 2048")) << w[0];
}

TEST(MapSizes, SweptSizesAndEntriesMarkedOwnMapSizeDoNotWarn) {
  EXPECT_EQ(warnings_for({{{"name", "shadow_map"}, {"params", {{"size", {512, 1024, 2048}}}}},
                          {{"name", "pcss"}, {"params", {{"size", 2048}}}}}),
            std::vector<std::string>{});
  EXPECT_EQ(warnings_for(
                {{{"name", "shadow_map"}, {"params", {{"size", 2048}}}},
                 {{"name", "accumulation"}, {"own_map_size", true}, {"params", {{"size", 512}}}}}),
            std::vector<std::string>{});
  EXPECT_THROW(warnings_for({{{"name", "accumulation"}, {"own_map_size", "yes"}}}), InputError);
}

TEST(MapSizes, ValidateAndPlanShowTheWarning) {
  const fs::path dir = fs::temp_directory_path() / "sb_map_sizes_cli";
  fs::create_directories(dir);
  const fs::path config = dir / "sizes.json";
  const std::string text = config_with({{{"name", "shadow_map"}, {"params", {{"size", 2048}}}},
                                        {{"name", "penumbra_maps"}, {"params", {{"size", 1024}}}}})
                               .dump();
  std::ofstream(config) << text;
  // The value 1024, on the file's one line.
  const std::string column = std::to_string(text.find("1024") + 1);
  for (const char* command : {"validate", "plan"}) {
    const CliResult r = run_cli(std::string(command) + " " + config.string());
    EXPECT_TRUE(has(r.output, "shadowbench: warning: " + config.string() + ":1:" + column +
                                  " (/techniques/1/params/size): technique "
                                  "penumbra_maps/size=1024 renders a 1024-texel map"))
        << command << ": " << r.output;
  }
}

TEST(MapSizes, NoShippedConfigComparesUnequalMaps) {
  ExperimentLimits limits;
  limits.max_jobs = uint64_t(1) << 40;
  size_t configs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SHADOWBENCH_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".json") continue;
    ++configs;
    const Experiment e = load_experiment(entry.path().string(), shipped(), limits);
    EXPECT_EQ(unequal_map_size_warnings(e), std::vector<std::string>{}) << entry.path();
  }
  EXPECT_GT(configs, 3u);
}

}  // namespace
}  // namespace sb::test
