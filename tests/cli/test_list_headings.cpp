// `shadowbench list NAME...` prints a heading only above what it heads.
#include <gtest/gtest.h>

#include <string>

#include "../config/cli_runner.h"

namespace sb::test {
namespace {

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

TEST(ListHeadings, ATechniqueAloneHasNoScenesHeading) {
  const auto r = run_cli("list pcss", false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has_line(r.output, "techniques:")) << r.output;
  EXPECT_FALSE(has_line(r.output, "scenes:")) << r.output;
}

TEST(ListHeadings, ASceneTypeAloneHasNoTechniquesHeading) {
  const auto r = run_cli("list sphere_grid", false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(has_line(r.output, "techniques:")) << r.output;
  EXPECT_TRUE(has_line(r.output, "scenes:")) << r.output;
}

TEST(ListHeadings, BothHaveBothHeadings) {
  const auto r = run_cli("list pcss sphere_grid", false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has_line(r.output, "techniques:")) << r.output;
  EXPECT_TRUE(has_line(r.output, "scenes:")) << r.output;
}

}  // namespace
}  // namespace sb::test
