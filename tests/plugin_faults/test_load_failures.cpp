// A plugin that fails to load is a warning naming it and the loader's
// message; the commands that do not need it work (exit 0), and a config
// naming a technique it may have registered says so (validate: exit 3).
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "../common/text.h"
#include "broken_plugins.h"
#include "plugin/registry.h"

namespace sb::test {

using plugin::Registry;

namespace {

TEST(PluginLoadFailures, AreRecordedWithTheFileAndTheLoadersMessageNotThrown) {
  const auto dir = broken_plugin_folder();
  Registry r;
  r.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  const size_t shipped = r.all().size();
  EXPECT_EQ(r.load_plugins(dir.string()), 0);
  ASSERT_EQ(r.load_failures().size(), 3u);
  // In file order: corrupt.so, half_registered.so, my_pcf.so.
  EXPECT_EQ(r.load_failures()[0].file, (dir / "corrupt.so").string());
  EXPECT_TRUE(has(r.load_failures()[0].message, "corrupt.so")) << r.load_failures()[0].message;
  EXPECT_EQ(r.load_failures()[1].file, (dir / "half_registered.so").string());
  EXPECT_TRUE(has(r.load_failures()[1].message, "'pcf_box' registered twice, first by"))
      << r.load_failures()[1].message;
  EXPECT_EQ(r.load_failures()[2].file, (dir / "my_pcf.so").string());
  EXPECT_TRUE(has(r.load_failures()[2].message, "undefined symbol"))
      << r.load_failures()[2].message;
  // What the clashing module registered before the clash is taken back; the
  // first module keeps its technique.
  EXPECT_EQ(r.find("half_registered"), nullptr);
  ASSERT_NE(r.find("pcf_box"), nullptr);
  EXPECT_EQ(r.find("pcf_box")->family, "shadow_map");
  EXPECT_EQ(r.all().size(), shipped);
  // The same folder again: each failure is said once.
  r.load_plugins(dir.string());
  EXPECT_EQ(r.load_failures().size(), 3u);
}

// A module built against an older plugin API names shadowbench symbols
// this build lacks: the failure says to rebuild it, and names the version. A
// module missing a symbol of its own gets no such hint.
TEST(PluginLoadFailures, AModuleOfAnotherPluginApiIsToldToRebuild) {
  Registry r;
  EXPECT_EQ(r.load_plugins(OLD_API_PLUGIN_DIR), 0);
  ASSERT_EQ(r.load_failures().size(), 1u);
  const std::string& message = r.load_failures()[0].message;
  EXPECT_TRUE(has(message, "undefined symbol: _ZN2sb26a_function_of_an_older_apiEv")) << message;
  EXPECT_TRUE(has(message, "built against another plugin API version; this build's is " +
                               std::to_string(plugin::kPluginApiVersion) +
                               ". Rebuild it against this shadowbench"))
      << message;

  // my_pcf.so lacks a function of its own (not in sb).
  Registry own;
  own.load_plugins(broken_plugin_folder().string());
  const auto it = std::find_if(own.load_failures().begin(), own.load_failures().end(),
                               [](const auto& f) { return f.file.ends_with("/my_pcf.so"); });
  ASSERT_NE(it, own.load_failures().end());
  EXPECT_TRUE(has(it->message, "undefined symbol")) << it->message;
  EXPECT_FALSE(has(it->message, "plugin API version")) << it->message;
}

TEST(PluginLoadFailures, ListWorksAndWarnsOncePerFailedModule) {
  const auto dir = broken_plugin_folder();
  for (const char* args : {"list", "list --names", "list pcf_box"}) {
    const CliRun r = shadowbench(dir.string(), args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
    EXPECT_TRUE(has(r.output, "pcf_box")) << r.output;
    for (const char* module : {"corrupt.so", "half_registered.so", "my_pcf.so"}) {
      const std::string warning =
          "shadowbench: warning: plugin " + (dir / module).string() + " failed to load: ";
      const size_t at = r.output.find(warning);
      EXPECT_NE(at, std::string::npos) << module << "\n" << r.output;
      EXPECT_EQ(r.output.find(warning, at + 1), std::string::npos) << "said twice:\n" << r.output;
    }
    EXPECT_TRUE(has(r.output, "undefined symbol")) << r.output;
  }
}

TEST(PluginLoadFailures, ValidateOfAConfigNotUsingTheBrokenPluginExitsZero) {
  const auto dir = broken_plugin_folder();
  const std::string config = small_config(dir, R"(["none", "pcf_box"])");
  const CliRun r = shadowbench(dir.string(), "validate " + config);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r.output, ": ok: ")) << r.output;
  EXPECT_TRUE(has(r.output, "warning: plugin " + (dir / "my_pcf.so").string() + " failed to load"))
      << r.output;
}

TEST(PluginLoadFailures, ValidateOfAConfigUsingItNamesThePluginAndItsMessage) {
  const auto dir = broken_plugin_folder();
  const std::string config =
      small_config(dir, R"(["none", {"name": "my_pcf", "params": {"k": [3, 5]}}])");
  const CliRun r = shadowbench(dir.string(), "validate " + config);
  EXPECT_EQ(r.exit_code, 3) << "an environment problem, as no plugins at all\n" << r.output;
  // file:LINE:COL (/techniques/1): the position is checked in tests/config.
  EXPECT_TRUE(has(r.output, config + ":")) << r.output;
  EXPECT_TRUE(has(r.output, " (/techniques/1): unknown technique \"my_pcf\" (plugin " +
                                (dir / "my_pcf.so").string() + " failed to load: "))
      << r.output;
  // The plan shows which jobs would fail, and why.
  const CliRun plan = shadowbench(dir.string(), "plan " + config);
  EXPECT_EQ(plan.exit_code, 3) << plan.output;
  EXPECT_TRUE(has(plan.output, "run  32x24  none")) << plan.output;
  EXPECT_TRUE(has(plan.output, "fail 32x24  my_pcf/k=3  (unknown technique \"my_pcf\" (plugin "))
      << plan.output;
  EXPECT_TRUE(has(plan.output, "fail 32x24  my_pcf/k=5")) << plan.output;
}

// A parameter enabled by a switch that is not there, or not a switch, is
// the plugin's mistake: refused when it registers, not when the stability
// suite reads it.
TEST(PluginLoadFailures, AParameterEnabledByNoSwitchIsRefusedWhenRegistered) {
  const auto info = [](std::vector<core::ParamSpec> params) {
    plugin::TechniqueInfo t;
    t.name = "switched";
    t.family = "test";
    t.params = std::move(params);
    return t;
  };
  core::ParamSpec length = core::float_param("length", 1.0, 0.0, 2.0, "a length");
  length.enabled_by = "on";
  Registry r;
  EXPECT_THROW(r.add(info({length})), std::logic_error);
  EXPECT_THROW(r.add(info({core::float_param("on", 1.0, 0.0, 2.0, "not a switch"), length})),
               std::logic_error);
  EXPECT_NO_THROW(r.add(info({core::bool_param("on", false, "the switch"), length})));
  length.enabled_by = "mode";
  plugin::TechniqueInfo choice =
      info({core::choice_param("mode", "none", {"none", "fast"}, "the switch"), length});
  choice.name = "switched_by_choice";
  EXPECT_NO_THROW(r.add(std::move(choice)));
}

}  // namespace
}  // namespace sb::test
