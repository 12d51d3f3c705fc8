// Parameters a technique declares but never reads (config/unread_params.h):
// reported for a plugin that has one, by validate and plan as well; none for
// the shipped techniques. No GL context exists in this test, so creating
// every shipped variant here also shows that no technique's constructor
// touches GL (glad's entry points are null until a context is made).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../common/text.h"
#include "cli_runner.h"
#include "config/unread_params.h"
#include "plugin/registry.h"

namespace sb::test {

using config::Experiment;
using config::ExperimentLimits;
using config::load_experiment;
using config::parse_experiment;
using config::unread_parameter_warnings;
using config::unread_parameters;
using core::resolve_params;
using plugin::Registry;
using plugin::TechniqueInfo;

namespace {

namespace fs = std::filesystem;

nlohmann::json reads_half_config(const nlohmann::json& params) {
  return {{"name", "unread"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 1}}}}}},
          {"techniques", {{{"name", "reads_half"}, {"params", params}}}},
          {"resolutions", {{16, 12}}},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 1}}}};
}

TEST(UnreadParams, ADeclaredParameterTheFactoryNeverReadsIsReportedPerVariant) {
  Registry r;
  r.load_plugins(UNREAD_PARAM_PLUGIN_DIR);
  const Experiment e =
      parse_experiment(reads_half_config({{"forgotten", {2, 4}}}), "unread.json", r);
  EXPECT_EQ(unread_parameters(*e.techniques[0].info, e.techniques[0].params),
            std::vector<std::string>{"forgotten"});
  const std::vector<std::string> warnings = unread_parameter_warnings(e);
  ASSERT_EQ(warnings.size(), 2u);
  for (const std::string& w : warnings) {
    EXPECT_TRUE(has(w, "unread.json: at /techniques/0")) << w;
    EXPECT_TRUE(has(w, "parameter 'forgotten' of reads_half")) << w;
    EXPECT_FALSE(has(w, "'used'")) << w;
  }
  EXPECT_TRUE(has(warnings[0], "technique reads_half/forgotten=2:")) << warnings[0];
  EXPECT_TRUE(has(warnings[1], "technique reads_half/forgotten=4:")) << warnings[1];
}

TEST(UnreadParams, ValidateAndPlanShowTheWarning) {
  const fs::path dir = fs::temp_directory_path() / "sb_unread_params_cli";
  fs::create_directories(dir);
  const fs::path config = dir / "unread.json";
  std::ofstream(config) << reads_half_config(nlohmann::json::object()).dump();
  for (const char* command : {"validate", "plan"}) {
    const CliResult r = run_cli(std::string(command) + " " + config.string() + " --plugins " +
                                UNREAD_PARAM_PLUGIN_DIR);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // The entry is the first of the list: line 1, after "techniques": [.
    const std::string text = reads_half_config(nlohmann::json::object()).dump();
    const std::string line_col =
        ":1:" + std::to_string(text.find('[', text.find("\"techniques\"")) + 2);
    EXPECT_TRUE(has(r.output, "shadowbench: warning: " + config.string() + line_col +
                                  " (/techniques/0): technique reads_half: parameter "
                                  "'forgotten' of reads_half is declared but never read"))
        << command << ": " << r.output;
  }
}

TEST(UnreadParams, NoShippedTechniqueLeavesADeclaredParameterUnread) {
  Registry r;
  r.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  ASSERT_FALSE(r.all().empty());
  for (const TechniqueInfo& t : r.all())
    EXPECT_EQ(unread_parameters(t, resolve_params(t.params, nullptr, "", "")),
              std::vector<std::string>{})
        << t.name << " with its defaults";
  ExperimentLimits limits;
  limits.max_jobs = uint64_t(1) << 40;
  size_t configs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SHADOWBENCH_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".json") continue;
    ++configs;
    const Experiment e = load_experiment(entry.path().string(), r, limits);
    EXPECT_EQ(unread_parameter_warnings(e), std::vector<std::string>{}) << entry.path();
  }
  EXPECT_GT(configs, 3u);
}

}  // namespace
}  // namespace sb::test
