// extended_light_maps (shadow_map/extended_light_map.h) on a small sphere
// grid under a near-point light: the 8-bit alpha depth shows acne (lit
// pixels the reference sees lit, called shadowed) that the 24-bit depth
// buffer does not, and the one-step alpha bias, the published remedy,
// removes most of it.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "e2e_util.h"

namespace sb::test {
namespace {

using json = nlohmann::json;

// Of the pixels the reference calls lit, the share the job calls umbra.
double acne_share(const json& record) {
  const json& lit = record["classes"]["counts"]["lit"];
  return lit[2].get<double>() /
         (lit[0].get<double>() + lit[1].get<double>() + lit[2].get<double>());
}

TEST(ExtendedLightMaps, EightBitAlphaDepthShowsAcneThatTheDepthBufferDoesNot) {
  const json config = {
      {"name", "extended_light_maps"},
      {"scenes",
       json::array({{{"type", "sphere_grid"}, {"params", {{"grid", 3}, {"light_size", 0.01}}}}})},
      {"techniques", json::array({{{"name", "extended_light_maps"},
                                   {"params",
                                    {{"shadow_channel", json::array({"alpha8", "24"})},
                                     {"alpha_bias", json::array({0.0, 1.0})}}}}})},
      {"resolutions", json::array({json::array({320, 240})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 16}}}};
  const auto out = run_config(config, "extended_light_maps_acne");
  ASSERT_EQ(out.summary.failed, 0);
  const auto share = [&](const char* channel, const char* bias) {
    return acne_share(out.record(std::string("extended_light_maps/shadow_channel=") + channel +
                                 ",alpha_bias=" + bias));
  };
  const double alpha8 = share("alpha8", "0.0"), alpha8_biased = share("alpha8", "1.0");
  const double depth24 = share("24", "0.0");
  std::printf("acne share: alpha8 %.5f, alpha8 with one step of bias %.5f, 24-bit %.5f\n", alpha8,
              alpha8_biased, depth24);
  EXPECT_GT(alpha8, 0.004);
  EXPECT_GT(alpha8, 10.0 * depth24);
  EXPECT_LT(depth24, 0.001);
  EXPECT_LT(alpha8_biased, 0.25 * alpha8);
  // The alpha bias means nothing to the depth buffer.
  EXPECT_EQ(share("24", "1.0"), depth24);
}

}  // namespace
}  // namespace sb::test
