// The hints: an unknown technique's nearest names and where plugins were
// looked for, a plugin folder with nothing in it, and `list`'s ranges and
// rules.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/text.h"
#include "broken_plugins.h"
#include "core/nearest_names.h"

namespace sb::test {

using core::did_you_mean;
using core::edit_distance;
using core::nearest_names;

namespace {

TEST(Hints, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // 2 substitutions, 1 insertion
  EXPECT_EQ(edit_distance("", "pcss"), 4u);
  EXPECT_EQ(edit_distance("pcss", "pcss"), 0u);
  EXPECT_EQ(edit_distance("pcf_bx", "pcf_box"), 1u);
}

TEST(Hints, NearestNamesAreTyposAndPartsNotEverything) {
  const std::vector<std::string> known = {"shadow_map", "pcf_box", "pcf_poisson", "pcss", "none"};
  EXPECT_EQ(nearest_names("pcf_bx", known), std::vector<std::string>({"pcf_box"}));
  EXPECT_EQ(nearest_names("pcs", known), std::vector<std::string>({"pcss"}));
  EXPECT_EQ(nearest_names("shadowmap", known), std::vector<std::string>({"shadow_map"}));
  EXPECT_TRUE(nearest_names("ray_traced", known).empty());
  EXPECT_EQ(did_you_mean("pcf", known), " did you mean pcf_box or pcf_poisson?");
  EXPECT_EQ(did_you_mean("ray_traced", known), "");
}

TEST(Hints, AWhollyReplacedNameIsNoTypo) {
  // One letter for another: every character differs, so nothing is near.
  EXPECT_TRUE(nearest_names("q", {"k", "n"}).empty());
  EXPECT_EQ(nearest_names("kk", {"k", "n"}), std::vector<std::string>({"k"}));
}

TEST(Hints, ANameExtendingAKnownOneIsNearOnlyWithExtensions) {
  const std::vector<std::string> known = {"pcf_box", "pcss", "none"};
  EXPECT_EQ(did_you_mean("pcss_stochastic", known), " did you mean pcss?");
  EXPECT_EQ(did_you_mean("pcss_stochastic", known, false), "");
  // Still a typo when within the edit distance, or a part of a known name.
  EXPECT_EQ(did_you_mean("pcss2", known, false), " did you mean pcss?");
  EXPECT_EQ(did_you_mean("box", known, false), " did you mean pcf_box?");
}

TEST(Hints, AnUnknownParameterSaysWhichWasMeant) {
  const auto dir = test_folder("sb_hints_");
  const std::string config =
      small_config(dir, R"([{"name": "pcss", "params": {"serch_taps": 3}}])");
  const CliRun r = shadowbench("", "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "unknown parameter 'serch_taps' (expected one of: ")) << r.output;
  EXPECT_TRUE(has(r.output, "); did you mean search_taps?")) << r.output;
}

// pcss_stochastic is a plugin's name that extends pcss's: not pcss mistyped,
// but a plugin not loaded. The hint says where plugins were looked for, and
// offers no pcss.
TEST(Hints, AnUnloadedPluginsTechniqueIsNotOfferedALoadedOne) {
  const auto dir = test_folder("sb_hints_");
  const std::string config = small_config(dir, R"(["none", "pcss_stochastic"])");
  const CliRun r = shadowbench("", "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "unknown technique \"pcss_stochastic\" (registered: ")) << r.output;
  EXPECT_FALSE(has(r.output, "did you mean")) << r.output;
  EXPECT_TRUE(has(r.output, "$SHADOWBENCH_PLUGIN_PATH is not set: only the plugins in "))
      << r.output;
  const CliRun list = shadowbench("", "list pcss_stochastic");
  EXPECT_EQ(list.exit_code, 2) << list.output;
  EXPECT_FALSE(has(list.output, "did you mean")) << list.output;
}

// new-technique's README builds the plugin into build/NAME.so beside the
// config: when it exists but is not loaded, the hint names its folder.
TEST(Hints, AnUnloadedScaffoldBuildIsNamedWithTheFolderToAdd) {
  const auto dir = test_folder("sb_hints_");
  std::filesystem::create_directories(dir / "build");
  std::ofstream(dir / "build" / "pcss_stochastic.so") << "not loaded";
  const std::string config = small_config(dir, R"(["none", "pcss_stochastic"])");
  const CliRun r = shadowbench("", "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string build = std::filesystem::absolute(dir / "build").string();
  EXPECT_TRUE(has(r.output, build +
                                "/pcss_stochastic.so (new-technique's build of it) would "
                                "provide it: export SHADOWBENCH_PLUGIN_PATH=" +
                                build))
      << r.output;
}

TEST(Hints, AnUnknownTechniqueNamesTheNearestAndSaysThePluginPathIsNotSet) {
  const auto dir = test_folder("sb_hints_");
  const std::string config = small_config(dir, R"(["none", "pcf_bx"])");
  const CliRun r = shadowbench("", "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "unknown technique \"pcf_bx\" (registered: ")) << r.output;
  EXPECT_TRUE(has(r.output, "did you mean pcf_box?")) << r.output;
  EXPECT_TRUE(has(r.output, "$SHADOWBENCH_PLUGIN_PATH is not set: only the plugins in "))
      << r.output;
  // From a build tree, the doc is the source's (an install names its own copy:
  // tests/install/install_and_relocate.py).
  EXPECT_TRUE(has(r.output, " were loaded (docs/install.md, \"Plugin folders\")")) << r.output;
}

TEST(Hints, APluginFolderWithNoPluginIsAWarningAndTheUnknownTechniqueSaysSo) {
  const auto dir = test_folder("sb_hints_");
  const auto empty = dir / "my_build";
  std::filesystem::create_directories(empty);
  const std::string config = small_config(dir, R"(["none", "my_pcf"])");
  const CliRun r = shadowbench(empty.string(), "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "shadowbench: warning: plugin folder " + empty.string() +
                                " (from $SHADOWBENCH_PLUGIN_PATH) holds no plugin (*.so)"))
      << r.output;
  EXPECT_TRUE(has(r.output, "$SHADOWBENCH_PLUGIN_PATH (" + empty.string() + ") loaded no plugin"))
      << r.output;
  // A command that needs no technique of it still works.
  const CliRun list = shadowbench(empty.string(), "list --names");
  EXPECT_EQ(list.exit_code, 0) << list.output;
  EXPECT_TRUE(has(list.output, "holds no plugin")) << list.output;
}

TEST(Hints, ListOfAnUnknownNameSaysWhichWasMeant) {
  const CliRun r = shadowbench("", "list pcf_bx");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "did you mean pcf_box?")) << r.output;
  EXPECT_TRUE(has(r.output, "$SHADOWBENCH_PLUGIN_PATH is not set")) << r.output;
}

TEST(Hints, PlainListShowsEachParametersRangeAndRules) {
  const CliRun r = shadowbench("", "list pcf_box pcss");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // k of pcf_box: its range and the "odd" rule, as the config reader checks them.
  EXPECT_TRUE(has(r.output, "kernel SIDE (odd), not a tap count: k² depth comparisons  [1 … "))
      << r.output;
  EXPECT_TRUE(has(r.output, ", odd]")) << r.output;
  EXPECT_TRUE(has(r.output, "[nearest, bilinear]")) << r.output;
  // pcss's search radius: 0 means "from the light's size".
  EXPECT_TRUE(has(r.output, "; 0 = chosen automatically]")) << r.output;
}

}  // namespace
}  // namespace sb::test
