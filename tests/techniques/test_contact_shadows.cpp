// Screen-space contact shadows (common/contact_shadow_pass.h), alone
// (contact_shadows) and as the option every listed map technique takes
// (common/contact_option.h), rendered through the harness's own stage
// (run/timing_contract.h) on scenes built here.
//   1. A plate at height h over a ground, the light straight above, the
//      camera under the plate's level so that it sees the ground beneath
//      it: a march of length L < h shadows no ground pixel; with L > h the
//      ground under the plate's interior is 0, and every ground point whose
//      march segment passes farther from the plate than the thickness (and
//      a few pixels) stays 1. The truth is the plate's box against the
//      segment from each ground point towards the light (CPU geometry).
//   2. technique + contact is min(technique, contact_shadows) in every
//      pixel: never above the technique, equal to it where contact sees
//      nothing; and the decorated technique keeps the timing contract.
//   3. The parameters are declared on every listed technique, validated
//      (length > 0, steps ≥ 1) and all read whether contact is on or off.
// With SB_CONTACT_IMAGES=<folder> set, the tests write V as PGM images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "config/unread_params.h"
#include "core/error.h"
#include "core/scene_types.h"
#include "debug_images.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::resolve_params;
using core::Scene;
using plugin::Registry;
using plugin::TechniqueInfo;
using run::ContractStage;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

// The plate: its bottom at 0.95, its top at 1.05.
constexpr float kPlateHeight = 1.0f;
const glm::vec3 kPlateCenter{0.0f, kPlateHeight, 0.0f};
const glm::vec3 kPlateHalf{1.0f, 0.05f, 1.0f};
constexpr int kSteps = 48;
constexpr float kThickness = 0.3f;

// `sun`: the sun straight above; else a small local light high above.
Scene plate_scene(bool sun) {
  Scene s;
  s.name = "contact_plate";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 6.0f));
  s.meshes.push_back(make_box("plate", kPlateCenter, kPlateHalf));
  s.light = sun ? core::make_sun_light({0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.01f, 40.0f)
                : core::make_area_light({0.0f, 30.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.5f, 0.5f);
  // Below the plate's bottom: the ground under it is in view.
  s.camera.eye = {0.3f, 0.45f, 3.2f};
  s.camera.target = {0.0f, 0.35f, 0.0f};
  s.camera.fov_y_degrees = 60.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 100.0f;
  return s;
}

// The distance from p to the plate's box (0 inside).
float distance_to_plate(const glm::vec3& p) {
  const glm::vec3 d = glm::max(glm::abs(p - kPlateCenter) - kPlateHalf, glm::vec3(0.0f));
  return glm::length(d);
}

// The least distance to the plate along the segment from p over `length`
// in direction `d`, sampled finely (a thousandth of the length).
float segment_distance_to_plate(const glm::vec3& p, const glm::vec3& d, float length) {
  float best = 1e30f;
  for (int i = 0; i <= 1000; ++i)
    best = std::min(best, distance_to_plate(p + d * (length * float(i) / 1000.0f)));
  return best;
}

// Whether the segment passes through the plate with `margin` to spare
// across it (the plate's footprint shrunk by `margin`).
bool segment_crosses_plate_interior(const glm::vec3& p, const glm::vec3& d, float length,
                                    float margin) {
  for (int i = 0; i <= 1000; ++i) {
    const glm::vec3 q = p + d * (length * float(i) / 1000.0f);
    if (std::abs(q.x - kPlateCenter.x) < kPlateHalf.x - margin &&
        std::abs(q.z - kPlateCenter.z) < kPlateHalf.z - margin &&
        std::abs(q.y - kPlateCenter.y) <= kPlateHalf.y)
      return true;
  }
  return false;
}

void maybe_write(const ImageF& img, const std::string& name) {
  write_pgm_if_asked(img, "SB_CONTACT_IMAGES", name);
}

class ContactShadows : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
  }
  const TechniqueInfo* find(const std::string& name) {
    const TechniqueInfo* info = plugins_.find(name);
    EXPECT_NE(info, nullptr) << name << " is not registered";
    return info;
  }
  void stage(Scene scene, const std::vector<const TechniqueInfo*>& infos) {
    stage_ = std::make_unique<ContractStage>(std::move(scene), kWidth, kHeight, infos, plugins_);
    for (size_t i = 0; i < infos.size(); ++i) EXPECT_EQ(stage_->skip_reason(i), "");
  }
  ImageF render(const TechniqueInfo* info, const nlohmann::json& params, const std::string& name) {
    const auto t = info->create(resolve_params(info->params, params, "", ""));
    t->prepare(stage_->inputs());
    ImageF v = stage_->render(*t);
    maybe_write(v, name);
    return v;
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<ContractStage> stage_;
};

// Test 1: see the top of the file.
TEST_F(ContactShadows, ReachOnlyTheirMarchLengthFromAnOccluder) {
  const TechniqueInfo* info = find("contact_shadows");
  ASSERT_NE(info, nullptr);
  for (const bool sun : {false, true}) {
    SCOPED_TRACE(sun ? "sun straight above" : "local light straight above");
    stage(plate_scene(sun), {info});
    const core::AreaLight light = stage_->scene().light;
    const ImageF position = stage_->read_gbuffer()[0];
    const ImageF normal = stage_->read_gbuffer()[1];
    const auto ground = [&](int x, int y) {
      return position.at(x, y, 3) != 0.0f && normal.at(x, y, 1) > 0.99f &&
             std::abs(position.at(x, y, 1)) < 1e-3f;
    };
    const auto towards_light = [&](const glm::vec3& p) {
      return sun ? light.to_sun() : glm::normalize(light.center - p);
    };

    // L < h: the march ends 0.3 below the plate's bottom.
    const float short_length = 0.6f;
    const ImageF short_v =
        render(info, {{"length", short_length}, {"steps", kSteps}, {"thickness", kThickness}},
               sun ? "contact_short_sun" : "contact_short_local");
    int ground_pixels = 0, dark = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (ground(x, y)) {
          ++ground_pixels;
          dark += short_v.at(x, y) < 0.5f;
        }
    EXPECT_GT(ground_pixels, 20000);
    EXPECT_EQ(dark, 0) << "of " << ground_pixels << " ground pixels with L < h";

    // L > h: through the plate.
    const float long_length = 1.5f;
    const ImageF long_v =
        render(info, {{"length", long_length}, {"steps", kSteps}, {"thickness", kThickness}},
               sun ? "contact_long_sun" : "contact_long_local");
    // A pixel's world size at the ground here is under 0.02: the margins
    // are several pixels, plus the start's offset off the surface.
    const float margin = 0.15f;
    int must_hit = 0, hit = 0, must_miss = 0, missed = 0;
    std::string first_wrong;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (!ground(x, y)) continue;
        const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
        const glm::vec3 d = towards_light(p);
        const float v = long_v.at(x, y);
        if (segment_crosses_plate_interior(p, d, long_length - margin, margin)) {
          ++must_hit;
          hit += v == 0.0f;
          if (v != 0.0f && first_wrong.empty())
            first_wrong = "V " + std::to_string(v) + " under the plate at (" + std::to_string(p.x) +
                          ", " + std::to_string(p.z) + ")";
        } else if (segment_distance_to_plate(p, d, long_length + margin) >
                   1.3f * kThickness + margin) {
          ++must_miss;
          missed += v == 1.0f;
          if (v != 1.0f && first_wrong.empty())
            first_wrong = "V " + std::to_string(v) + " far from the plate at (" +
                          std::to_string(p.x) + ", " + std::to_string(p.z) + ")";
        }
      }
    EXPECT_GT(must_hit, 1000);
    EXPECT_GT(must_miss, 5000);
    EXPECT_EQ(hit, must_hit) << first_wrong;
    EXPECT_EQ(missed, must_miss) << first_wrong;
    std::printf("%s: %d ground pixels under the plate, %d far from it\n", sun ? "sun" : "local",
                must_hit, must_miss);
  }
}

// A plate 1.5 over the ground under a 2-unit light close above: wide
// penumbrae, which contact shadows (hard, from the light's centre) darken
// under the plate's edge.
Scene penumbra_scene() {
  Scene s = plate_scene(false);
  s.meshes[1] = make_box("plate", {0.0f, 1.5f, 0.0f}, kPlateHalf);
  s.light = core::make_area_light({0.5f, 5.0f, 0.3f}, {0.0f, 0.0f, 0.0f}, 2.0f, 2.0f);
  s.camera.eye = {0.3f, 0.9f, 3.5f};
  return s;
}

// The penumbra scene under the sun, 2° across, from the local light's
// direction: for the techniques that run only under the sun.
Scene sun_penumbra_scene() {
  Scene s = penumbra_scene();
  s.light = core::make_sun_light(glm::normalize(glm::vec3(0.5f, 5.0f, 0.3f)), {0.0f, 0.0f, 0.0f},
                                 glm::radians(2.0f), 6.0f);
  return s;
}

// Test 2: see the top of the file.
TEST_F(ContactShadows, WithAMapTechniqueAreTheMinimumOfBoth) {
  const TechniqueInfo* contact = find("contact_shadows");
  ASSERT_NE(contact, nullptr);
  const nlohmann::json march = {{"length", 2.0}, {"steps", 32}, {"thickness", 0.3}};
  const auto expect_minimum = [&](const char* name, const Scene& scene) {
    SCOPED_TRACE(name);
    const TechniqueInfo* info = find(name);
    ASSERT_NE(info, nullptr);
    stage(scene, {info, contact});
    const nlohmann::json map_params = {{"size", 512}};
    nlohmann::json with_contact = map_params;
    with_contact["contact"] = true;
    for (const auto& [key, value] : march.items()) with_contact["contact_" + key] = value;
    const ImageF alone = render(info, map_params, name);
    const ImageF combined = render(info, with_contact, std::string(name) + "_contact");
    const ImageF v_contact = render(contact, march, "contact_penumbra");
    int darkened = 0, above = 0, not_min = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const float a = alone.at(x, y), c = combined.at(x, y), k = v_contact.at(x, y);
        above += c > a;
        not_min += c != std::min(a, k);
        darkened += k < a - 0.05f;
      }
    // Contact must matter somewhere, or the test shows nothing.
    EXPECT_GT(darkened, 200);
    EXPECT_EQ(above, 0) << "pixels where " << name << "+contact is above " << name;
    EXPECT_EQ(not_min, 0) << "pixels where " << name << "+contact is not min(" << name
                          << ", contact_shadows)";
  };
  for (const char* name : {"pcss", "shadow_map", "vsm"}) expect_minimum(name, penumbra_scene());
  // The techniques of the sun take it as well (along to_sun()).
  for (const char* name : {"cascaded_shadow_map", "sdsm", "virtual_shadow_map"})
    expect_minimum(name, sun_penumbra_scene());
}

// A technique with the option on keeps the contract every built-in keeps.
TEST_F(ContactShadows, DecoratedTechniqueKeepsTheTimingContract) {
  const TechniqueInfo* info = find("pcss");
  ASSERT_NE(info, nullptr);
  stage_ =
      std::make_unique<ContractStage>(run::contract_scene(), 96, 72, std::vector{info}, plugins_);
  const core::Params p = resolve_params(info->params, {{"size", 256}, {"contact", true}}, "", "");
  for (const run::ContractCheck& c : run::check_timing_contract(
           *stage_, [&] { return info->create(p); }, true))
    EXPECT_TRUE(c.passed()) << c.name << ": " << c.failure;
}

// Test 3: see the top of the file.
TEST_F(ContactShadows, ParametersAreDeclaredValidatedAndRead) {
  for (const char* name :
       {"shadow_map", "pcf_box", "pcf_gauss", "pcf_jitter", "pcss", "vsm", "esm", "evsm", "msm",
        "csm_convolution", "cascaded_shadow_map", "sdsm", "virtual_shadow_map"}) {
    SCOPED_TRACE(name);
    const TechniqueInfo* info = find(name);
    ASSERT_NE(info, nullptr);
    const core::Params defaults = resolve_params(info->params, nullptr, "", "");
    EXPECT_FALSE(defaults.json().at("contact").get<bool>());
    for (const char* key : {"contact_length", "contact_steps", "contact_thickness"})
      EXPECT_TRUE(defaults.json().contains(key)) << key;
    EXPECT_THROW(resolve_params(info->params, {{"contact_length", 0.0}}, "c.json", "/p"),
                 core::InputError);
    EXPECT_THROW(resolve_params(info->params, {{"contact_length", -1.0}}, "c.json", "/p"),
                 core::InputError);
    EXPECT_THROW(resolve_params(info->params, {{"contact_steps", 0}}, "c.json", "/p"),
                 core::InputError);
    EXPECT_THROW(resolve_params(info->params, {{"contact_thickness", 0.0}}, "c.json", "/p"),
                 core::InputError);
    for (const bool on : {false, true})
      EXPECT_EQ(
          config::unread_parameters(*info, resolve_params(info->params, {{"contact", on}}, "", "")),
          std::vector<std::string>{})
          << "contact " << on;
  }
  const TechniqueInfo* contact = find("contact_shadows");
  ASSERT_NE(contact, nullptr);
  EXPECT_THROW(resolve_params(contact->params, {{"length", 0.0}}, "c.json", "/p"),
               core::InputError);
  EXPECT_THROW(resolve_params(contact->params, {{"steps", 0}}, "c.json", "/p"), core::InputError);
  EXPECT_NO_THROW(resolve_params(contact->params, {{"length", 0.01}, {"steps", 1}}, "", ""));
  EXPECT_EQ(config::unread_parameters(*contact, resolve_params(contact->params, nullptr, "", "")),
            std::vector<std::string>{});
}

}  // namespace
}  // namespace sb::test
