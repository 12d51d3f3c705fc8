// Parameter docs come from the ParamSpecs: docs/parameters.md must be
// exactly what `shadowbench list --markdown` prints, and the table says
// what the config reader accepts.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cli_runner.h"
#include "config/param_table.h"

namespace sb::test {

using config::markdown_param_table;
using core::choice_param;
using core::float_param;
using core::int_param;
using core::odd;
using core::ParamSpec;

namespace {

TEST(ParamDocs, TheDocsFileIsTheGeneratedOne) {
  std::ifstream in(std::string(SHADOWBENCH_SOURCE_DIR) + "/docs/parameters.md");
  std::stringstream file;
  file << in.rdbuf();
  const auto r = run_cli("list --markdown");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file.str(), r.output)
      << "regenerate it: build/shadowbench list --markdown > docs/parameters.md";
}

TEST(ParamDocs, TheTableSaysWhatIsAccepted) {
  ParamSpec k = odd(int_param("k", 5, 1, 63, "kernel side | in texels"));
  const std::string table =
      markdown_param_table({k, choice_param("cull", "front", {"none", "front"}, "culled faces"),
                            float_param("sigma", 0.0, 0.0, 64.0, "blur")});
  EXPECT_NE(table.find("| `k` | integer | `5` | 1 … 63, odd | kernel side \\| in texels |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| `cull` | choice | `\"front\"` | `none`, `front` | culled faces |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| `sigma` | number | `0.0` | 0 … 64 | blur |"), std::string::npos) << table;
}

}  // namespace
}  // namespace sb::test
