// psm and lispsm (shadow_map/perspective_warp.h) on the long_ground scene,
// whose light is small enough (1e-3 of the strip) for the reference to be a
// hard shadow: against the uniform shadow_map of the same size near the
// camera, and with the light behind the camera (the inverted projection and
// the virtual camera moved back).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "e2e_util.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

json experiment(const json& scene_params, int map_size) {
  json techniques = json::array();
  for (const char* name : {"shadow_map", "psm", "lispsm"})
    techniques.push_back({{"name", name}, {"params", {{"size", map_size}}}});
  return {{"name", "perspective_maps"},
          {"scenes", json::array({{{"type", "long_ground"}, {"params", scene_params}}})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({320, 240})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}}},
          {"metrics", {{"distance_thirds", true}}}};
}

double rmse(const json& record, const char* region) {
  return record["metrics"]["visibility"][region]["rmse"].get<double>();
}

std::string variant(const char* name, int size) {
  return std::string(name) + "/size=" + std::to_string(size);
}

TEST(PerspectiveMaps, NearTheCameraBothWarpsErrLessThanTheUniformMapOfTheSameSize) {
  const int size = 512;
  const auto out = run_config(experiment(json::object(), size), "perspective_maps_near");
  ASSERT_EQ(out.summary.failed, 0);
  const double uniform = rmse(out.record(variant("shadow_map", size)), "near_third");
  for (const char* warped : {"psm", "lispsm"}) {
    const json& r = out.record(variant(warped, size));
    std::printf("%-7s near %.4f middle %.4f far %.4f (shadow_map near %.4f)\n", warped,
                rmse(r, "near_third"), rmse(r, "middle_third"), rmse(r, "far_third"), uniform);
    EXPECT_GT(r["metrics"]["visibility"]["near_third"]["pixel_count"].get<int>(), 10000);
    EXPECT_LT(rmse(r, "near_third"), 0.75 * uniform) << warped;
  }
}

// Behind the camera the light's post-perspective image lies past infinity:
// a PSM that kept the ordinary depth order would shadow the lit side of
// every occluder and light the ground behind it (an inverted shadow), and a
// post behind the camera, whose shadow falls into view, would be lost
// without the virtual camera's shift.
TEST(PerspectiveMaps, ALightBehindTheCameraGivesFiniteUninvertedShadows) {
  const int size = 1024;
  const auto out = run_config(experiment({{"light", "behind"}}, size), "perspective_maps_behind");
  ASSERT_EQ(out.summary.failed, 0);
  for (const char* name : {"shadow_map", "psm", "lispsm"}) {
    const json& r = out.record(variant(name, size));
    EXPECT_EQ(r["visibility_check"]["nonfinite"].get<int>(), 0) << name;
    const json& c = r["classes"]["counts"];
    const double umbra =
        c["umbra"][0].get<double>() + c["umbra"][1].get<double>() + c["umbra"][2].get<double>();
    const double lit =
        c["lit"][0].get<double>() + c["lit"][1].get<double>() + c["lit"][2].get<double>();
    // Of the reference's umbra, the share the technique calls lit; of its
    // lit pixels, the share the technique calls umbra.
    const double umbra_lit = c["umbra"][0].get<double>() / umbra;
    const double lit_umbra = c["lit"][2].get<double>() / lit;
    std::printf("%-10s rmse %.4f, umbra called lit %.4f, lit called umbra %.5f\n", name,
                rmse(r, "all"), umbra_lit, lit_umbra);
    EXPECT_GT(umbra, 300.0);
    EXPECT_LT(umbra_lit, 0.1) << name;
    EXPECT_LT(lit_umbra, 0.005) << name;
  }
  // The post behind the camera shadows the image's bottom rows: the warped
  // maps keep it (the reference's umbra there is theirs too).
  const ImageF ref = out.reference_visibility();
  for (const char* name : {"psm", "lispsm"}) {
    const ImageF v = out.visibility(variant(name, size));
    int ref_dark = 0, both_dark = 0;
    for (int y = 0; y < ref.height / 10; ++y)  // row 0 is the image's top
      for (int x = 0; x < ref.width; ++x) {
        const size_t i = size_t(ref.height - 1 - y) * size_t(ref.width) + size_t(x);
        if (ref.data[i] < 0.5f) {
          ++ref_dark;
          both_dark += v.data[i] < 0.5f ? 1 : 0;
        }
      }
    EXPECT_GT(ref_dark, 200);  // 354 at 320×240
    EXPECT_GT(double(both_dark), 0.9 * ref_dark) << name;
  }
}

}  // namespace
}  // namespace sb::test
