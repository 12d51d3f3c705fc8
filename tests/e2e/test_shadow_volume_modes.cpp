// shadow_volume's stencil modes (z-pass, z-fail, auto), its silhouette
// extraction on the GPU or the CPU, and its pass split, against the
// ray-traced reference of a near-point light.
#include <gtest/gtest.h>

#include "core/error.h"
#include "e2e_util.h"
#include "metrics/metrics.h"

namespace sb::test {

using core::ImageF;
using core::InputError;
using run::RunOptions;

namespace {

using json = nlohmann::json;

json experiment(const json& scene, const json& techniques) {
  return {{"name", "sv"},
          {"scenes", json::array({scene})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({160, 120})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}}}};
}

double rmse(const RunOutput& out, const std::string& variant) {
  return out.record(variant)["metrics"]["visibility"]["all"]["rmse"].get<double>();
}

// One sphere over the ground; the eye just under it, on the line from the
// light through its centre, looking down that line with a wide lens: the near
// plane lies inside the sphere's shadow volume, and the view holds the whole
// shadow with lit ground around it.
TEST(ShadowVolumeModes, ACameraInsideAVolumeIsRightInZFailAndAutoAndWrongInZPass) {
  // sphere_grid with grid 1: the sphere (radius 0.5) at (0, 1.2, 0), the
  // light at 10·(0.35, 1, 0.25).
  const glm::vec3 light(3.5f, 10.0f, 2.5f), centre(0.0f, 1.2f, 0.0f);
  const glm::vec3 down = glm::normalize(centre - light);
  const glm::vec3 eye = centre + 0.6f * down, target = centre + 2.0f * down;
  const json scene = {{"type", "sphere_grid"},
                      {"params", {{"grid", 1}, {"light_size", 1e-3}}},
                      {"camera",
                       {{"eye", {eye.x, eye.y, eye.z}},
                        {"target", {target.x, target.y, target.z}},
                        {"fov_y", 120.0},
                        {"near", 0.01}}}};
  const auto out = run_config(
      experiment(scene, json::array({json{{"name", "shadow_volume"},
                                          {"params",
                                           {{"mode", json::array({"zpass", "zfail", "auto"})},
                                            {"silhouettes", json::array({"gpu", "cpu"})}}}}})),
      "sv_camera_inside");
  ASSERT_EQ(out.summary.failed, 0);
  // The view holds both shadow and lit ground.
  const ImageF truth = out.reference_visibility();
  size_t dark = 0;
  for (float v : truth.data) dark += v < 0.5f;
  EXPECT_GT(dark, truth.pixel_count() / 10);
  EXPECT_LT(dark, truth.pixel_count() * 9 / 10);
  for (const char* where : {"gpu", "cpu"}) {
    const auto name = [&](const char* mode) {
      return "shadow_volume/mode=" + std::string(mode) + ",silhouettes=" + where;
    };
    const double zpass = rmse(out, name("zpass")), zfail = rmse(out, name("zfail")),
                 automatic = rmse(out, name("auto"));
    // Hard against hard: only shadow-boundary pixels may differ.
    EXPECT_LT(zfail, 0.1) << where;
    EXPECT_LT(automatic, 0.1) << where;
    // Counting from a camera inside the volume inverts lit and shadowed.
    EXPECT_GT(zpass, 0.3) << where << ": z-pass RMSE " << zpass << " (z-fail " << zfail << ")";
    RecordProperty(std::string("zpass_rmse_") + where, std::to_string(zpass));
  }
}

TEST(ShadowVolumeModes, AllModesAgreeWhenTheCameraIsOutsideEveryVolume) {
  const auto out =
      run_config(experiment(small_scene(1e-3),
                            json::array({json{{"name", "shadow_volume"},
                                              {"params",
                                               {{"mode", json::array({"zpass", "zfail", "auto"})},
                                                {"silhouettes", json::array({"gpu", "cpu"})}}}}})),
                 "sv_camera_outside");
  ASSERT_EQ(out.summary.failed, 0);
  const ImageF base = out.visibility("shadow_volume/mode=zfail,silhouettes=gpu");
  size_t dark = 0;
  for (float v : base.data) dark += v < 0.5f;
  ASSERT_GT(dark, base.pixel_count() / 20) << "the shadows are there";
  for (const char* mode : {"zpass", "zfail", "auto"})
    for (const char* where : {"gpu", "cpu"}) {
      const std::string v =
          "shadow_volume/mode=" + std::string(mode) + ",silhouettes=" + std::string(where);
      const auto s = metrics::compare(out.visibility(v), base);
      EXPECT_LT(s.frac_over_01, 0.001) << v;
      EXPECT_LT(rmse(out, v), 0.1) << v;
    }
}

TEST(ShadowVolumeModes, TheCpuPathTimesExtractionExtrusionUploadStencilAndResolve) {
  const auto out = run_config_with(
      experiment(
          small_scene(1e-3),
          json::array(
              {json{{"name", "shadow_volume"},
                    {"params",
                     {{"silhouettes", json::array({"gpu", "cpu"})}, {"silhouette", "discrete"}}}},
               json{{"name", "shadow_volume"},
                    {"params", {{"silhouettes", "cpu"}, {"silhouette", "smooth"}}}}})),
      "sv_passes", [](RunOptions& o) { o.pass_detail = gl::PassDetail::Fine; });
  ASSERT_EQ(out.summary.failed, 0);
  const auto passes = [&](const std::string& v) {
    std::vector<std::string> names;
    for (const auto& p : out.record(v)["timing"]["pass_order"]) names.push_back(p);
    return names;
  };
  const std::vector<std::string> cpu = {"silhouettes", "extrusion", "upload", "stencil", "resolve"};
  EXPECT_EQ(passes("shadow_volume/silhouettes=cpu,silhouette=discrete"), cpu);
  EXPECT_EQ(passes("shadow_volume/silhouettes=cpu,silhouette=smooth"), cpu);
  EXPECT_EQ(passes("shadow_volume/silhouettes=gpu,silhouette=discrete"),
            (std::vector<std::string>{"stencil", "resolve"}));
}

TEST(ShadowVolumeModes, SmoothSilhouettesNeedTheCpuPath) {
  const json config = experiment(
      small_scene(1e-3),
      json::array({json{{"name", "shadow_volume"}, {"params", {{"silhouette", "smooth"}}}}}));
  try {
    run_config(config, "sv_smooth_gpu");
    FAIL() << "smooth silhouettes on the GPU path were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("silhouette"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"cpu\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sb::test
