// Alpha-tested casters: light passes through the transparent texels of a
// leaf quad, in the ray-traced reference and in shadow maps alike. Measured
// on a single leaf over the ground under a near-point light, against the
// analytic answer: follow each ground pixel's ray to the light's centre
// through the leaf's plane and read the mask texel it crosses.
#include <gtest/gtest.h>

#include <cmath>

#include "core/scene_types.h"
#include "e2e_util.h"
#include "scenes/leaf.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::add_scene_type;
using core::AlphaMode;
using core::bool_param;
using core::find_scene_type;
using core::ImageF;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::sample_alpha;
using core::Scene;
using core::TextureImage;

namespace {

using json = nlohmann::json;

constexpr float kLeafHeight = 1.0f;
constexpr float kLeafHalf = 0.6f;
const glm::vec3 kLight(1.5f, 6.0f, 0.5f);

Scene single_leaf(const Params& p) {
  Scene s;
  s.name = "single_leaf";
  s.textures.push_back(make_leaf_texture(64, 1));
  Mesh leaf = make_leaf_quad("leaf", glm::vec3(0, kLeafHeight, 0), glm::vec3(kLeafHalf, 0, 0),
                             glm::vec3(0, 0, kLeafHalf), 0);
  if (!p.get_bool("alpha_test")) leaf.alpha_mode = AlphaMode::Opaque;
  s.meshes.push_back(leaf);
  Mesh ground = make_ground_plane("ground", glm::vec3(0), 6.0f);
  s.meshes.push_back(ground);
  s.light = make_area_light(kLight, glm::vec3(0), 0.01f, 0.01f);
  // Looking down at the leaf's shadow from the side opposite the light, so
  // that the leaf itself hides little of it.
  s.camera.eye = glm::vec3(-2.6f, 3.2f, -0.6f);
  s.camera.target = glm::vec3(-0.3f, 0.0f, -0.1f);
  s.camera.fov_y_degrees = 40.0f;
  return s;
}

struct Agreement {
  size_t through_holes = 0;  // ground pixels whose ray crosses a transparent texel
  size_t through_leaf = 0;   // ... an opaque texel
  double agree_holes = 0.0;  // share of those where V > 0.5
  double agree_leaf = 0.0;   // share of those where V < 0.5
};

Agreement check(const ImageF& positions, const ImageF& visibility, const TextureImage& mask) {
  Agreement a;
  size_t lit = 0, dark = 0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    const glm::vec3 p(positions.data[4 * i], positions.data[4 * i + 1], positions.data[4 * i + 2]);
    if (positions.data[4 * i + 3] == 0.0f || std::fabs(p.y) > 1e-4f) continue;  // ground only
    const float t = (kLeafHeight - p.y) / (kLight.y - p.y);
    const glm::vec3 q = p + t * (kLight - p);
    const glm::vec2 uv((q.x + kLeafHalf) / (2 * kLeafHalf), (q.z + kLeafHalf) / (2 * kLeafHalf));
    if (uv.x < 0 || uv.x >= 1 || uv.y < 0 || uv.y >= 1) continue;
    // Skip rays within a tenth of a texel of a texel edge: there the 0.01
    // light's penumbra and rounding may go either way.
    const float fx = uv.x * float(mask.width), fy = uv.y * float(mask.height);
    if (std::fabs(fx - std::round(fx)) < 0.1f || std::fabs(fy - std::round(fy)) < 0.1f) continue;
    if (sample_alpha(mask, uv) < 0.5f) {
      ++a.through_holes;
      lit += visibility.data[i] > 0.5f;
    } else {
      ++a.through_leaf;
      dark += visibility.data[i] < 0.5f;
    }
  }
  a.agree_holes = a.through_holes ? double(lit) / double(a.through_holes) : 0.0;
  a.agree_leaf = a.through_leaf ? double(dark) / double(a.through_leaf) : 0.0;
  return a;
}

class AlphaMasks : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (find_scene_type("test_single_leaf") == nullptr)
      add_scene_type({"test_single_leaf",
                      "one alpha-tested leaf over the ground",
                      {bool_param("alpha_test", true, "honour the leaf's mask")},
                      single_leaf});
  }
  static json config(bool alpha_test) {
    return {{"name", "leaf"},
            {"scenes", {{{"type", "test_single_leaf"}, {"params", {{"alpha_test", alpha_test}}}}}},
            {"techniques", {{{"name", "shadow_map"}, {"params", {{"size", 2048}}}}}},
            {"resolutions", {{200, 150}}},
            {"frames", {{"warmup", 0}, {"timed", 1}}},
            {"reference", {{"spp", 16}}}};
  }
};

TEST_F(AlphaMasks, LightPassesThroughTransparentTexels) {
  const auto out = run_config(config(true), "single_leaf", gl::Backend::OSMesa, true, true);
  ASSERT_EQ(out.summary.failed, 0) << out.records[0].dump();
  const ImageF positions = out.gbuffer_positions();
  const TextureImage mask = make_leaf_texture(64, 1);
  for (const auto& [name, v] : {std::pair{"reference", out.reference_visibility()},
                                std::pair{"shadow_map", out.visibility("shadow_map/size=2048")}}) {
    const Agreement a = check(positions, v, mask);
    // The measurement covers enough of both kinds of texel to mean something.
    EXPECT_GT(a.through_holes, 300u) << name;
    EXPECT_GT(a.through_leaf, 300u) << name;
    EXPECT_GT(a.agree_holes, 0.97) << name << ": light through the holes";
    EXPECT_GT(a.agree_leaf, 0.97) << name << ": shadow of the blade";
  }
}

TEST_F(AlphaMasks, WithoutTheMaskTheWholeQuadShadows) {
  const auto out = run_config(config(false), "single_leaf_opaque", gl::Backend::OSMesa, true, true);
  ASSERT_EQ(out.summary.failed, 0);
  const Agreement a = check(out.gbuffer_positions(), out.visibility("shadow_map/size=2048"),
                            make_leaf_texture(64, 1));
  EXPECT_LT(a.agree_holes, 0.03);  // the holes are dark now
}

}  // namespace
}  // namespace sb::test
