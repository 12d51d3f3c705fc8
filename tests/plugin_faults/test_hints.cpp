// The hints: an unknown technique's nearest names and where plugins were
// looked for, a plugin folder with nothing in it, and `list`'s ranges and
// rules.
#include <gtest/gtest.h>

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

TEST(Hints, AnUnknownTechniqueNamesTheNearestAndSaysThePluginPathIsNotSet) {
  const auto dir = test_folder("sb_hints_");
  const std::string config = small_config(dir, R"(["none", "pcf_bx"])");
  const CliRun r = shadowbench("", "validate " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "unknown technique \"pcf_bx\" (registered: ")) << r.output;
  EXPECT_TRUE(has(r.output, "did you mean pcf_box?")) << r.output;
  EXPECT_TRUE(has(r.output, "$SHADOWBENCH_PLUGIN_PATH is not set: only the plugins in "))
      << r.output;
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
  EXPECT_TRUE(has(r.output, "kernel side (odd): k*k depth comparisons  [1 … ")) << r.output;
  EXPECT_TRUE(has(r.output, ", odd]")) << r.output;
  EXPECT_TRUE(has(r.output, "[nearest, bilinear]")) << r.output;
  // pcss's search radius: 0 means "from the light's size".
  EXPECT_TRUE(has(r.output, "; 0 = chosen automatically]")) << r.output;
}

}  // namespace
}  // namespace sb::test
