// occlusion_textures (techniques/occlusion_texture/): the summed-area table
// against the exact box filter of a plate's rasterised texture, the three
// ways of combining slices where two occluders' penumbrae overlap, the
// thin-occluder fix under a plate that slopes across slices, the far-plane
// lookup and the self-slab rules against their closed forms, and finite
// visibility at extreme light sizes, with kernels larger
// than the texture and points on the slices' boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "../gltf/gltf_builder.h"
#include "e2e_util.h"
#include "occlusion_texture/slicing.h"
#include "plate_scenes.h"
#include "scenes/mesh_builders.h"

namespace sb::test {

using core::AreaLight;
using core::ImageF;
using core::Mesh;
using core::Scene;
namespace occlusion_texture = techniques::occlusion_texture;

namespace {

using json = nlohmann::json;

json occlusion_experiment(const json& scenes, const json& techniques, int spp, int width,
                          int height) {
  return {{"name", "occlusion_textures"},
          {"scenes", scenes},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({width, height})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", spp}}}};
}

json occlusion_textures(const json& params) {
  return {{"name", "occlusion_textures"}, {"params", params}};
}

// The light facing straight down, as plate_scenes.h places it, for the CPU
// slicing.
AreaLight plate_light(float size) {
  AreaLight l;
  l.center = {0.0f, kLightHeight, 0.0f};
  l.target = {0.0f, 0.0f, 0.0f};
  l.half_u = {0.5f * size, 0.0f, 0.0f};
  l.half_v = {0.0f, 0.0f, 0.5f * size};
  return l;
}

// One plate parallel to the light. A texel of the slice holding its top face
// is 1 where its centre lies in the face's projection (GL's rasterisation
// rule); the SAT's answer must be that texture's exact mean over the light
// seen from each ground point, fractional texels included, to 1/size. It
// must also be the true V to within the shift of an edge by half a texel.
TEST(OcclusionTextures, TheSummedAreaTableGivesTheExactBoxFilteredOcclusionOfAPlanarOccluder) {
  TempDir dir;
  const Plate plate{-0.45f, 0.8f, -0.7f, 0.35f, 1.0f, 1e-3f};
  const float size = 1.0f;
  const int texels = 256;
  const auto out = run_config(
      occlusion_experiment(
          json::array({plate_scene(write_plates(dir.path, {plate}, {0.0f, 4.0f, 3.0f}), size)}),
          json::array({occlusion_textures(
              {{"size", texels}, {"slices", 4}, {"self_slab", "skip"}, {"lookup_plane", "far"}})}),
          4, 160, 120),
      "occlusion_planar", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 1) << out.records.at(0).value("reason", "");
  // The same slicing on the CPU: one caster, the plate.
  Scene scene;
  scene.light = plate_light(size);
  scene.meshes.push_back(
      make_box("plate", {0.5f * (plate.x0 + plate.x1), plate.h, 0.5f * (plate.z0 + plate.z1)},
               {0.5f * (plate.x1 - plate.x0), plate.half_thickness, 0.5f * (plate.z1 - plate.z0)}));
  const occlusion_texture::Slicing slicing =
      occlusion_texture::fit_slicing(scene, 4, occlusion_texture::Projection::Central);
  const float top = plate.h + plate.half_thickness;
  const glm::vec2 a = slicing.texture_coords(slicing.light.to_light({plate.x0, top, plate.z0}));
  const glm::vec2 b = slicing.texture_coords(slicing.light.to_light({plate.x1, top, plate.z1}));
  const glm::vec2 face_lo = glm::min(a, b) * float(texels),
                  face_hi = glm::max(a, b) * float(texels);
  const int top_slab =
      int(std::floor((slicing.light.to_light({0, top, 0}).z - slicing.z0) / slicing.thickness));
  // The mean over [lo, hi] of texels whose centres lie in the face, per axis.
  const auto covered = [&](float lo, float hi, float face0, float face1) {
    double sum = 0.0;
    for (int i = int(std::floor(lo)); i <= int(std::floor(hi)); ++i) {
      const float centre = float(i) + 0.5f;
      if (i < 0 || i >= texels || centre < face0 || centre > face1) continue;
      sum += std::max(0.0, std::min<double>(hi, i + 1) - std::max<double>(lo, i));
    }
    return sum;
  };
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  const ImageF v = out.visibility(out.records.at(0)["technique"]["variant"]);
  size_t n = 0, penumbra = 0;
  double worst_filter = 0.0, worst_edge = 0.0;
  for (size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) continue;
    const glm::vec3 p(positions.data[i * 4], positions.data[i * 4 + 1], positions.data[i * 4 + 2]);
    const glm::vec3 pl = slicing.light.to_light(p);
    double box_filtered = 1.0;
    double texel_over_kernel = 0.0;
    for (int k = 0; k < 4; ++k) {
      if (k != top_slab) continue;  // the bottom face is not light-facing: not drawn
      // The ground lies more than a slice below the plate: the skip rule's
      // offset leaves it the whole slab, read through the slice's far plane.
      const occlusion_texture::SlabShare share = slicing.share(
          pl.z, k, occlusion_texture::point_offset(occlusion_texture::SelfSlab::Skip, false, 1.0f),
          occlusion_texture::LookupPlane::Far);
      const float w = share.weight;
      const occlusion_texture::TextureBox box = slicing.kernel(pl, share.plane);
      const glm::vec2 lo = box.lo * float(texels), hi = box.hi * float(texels);
      const double area = double(hi.x - lo.x) * double(hi.y - lo.y);
      box_filtered = 1.0 - w * covered(lo.x, hi.x, face_lo.x, face_hi.x) *
                               covered(lo.y, hi.y, face_lo.y, face_hi.y) / area;
      texel_over_kernel = 1.0 / double(std::min(hi.x - lo.x, hi.y - lo.y));
    }
    const double exact = exact_visibility(plate, p.x, p.z, size);
    worst_filter = std::max(worst_filter, std::abs(double(v.data[i]) - box_filtered));
    // Each of the two edges a kernel crosses may move by half a texel.
    worst_edge = std::max(worst_edge, std::abs(double(v.data[i]) - exact) / texel_over_kernel);
    ++n;
    penumbra += exact > 0.01 && exact < 0.99;
  }
  std::printf(
      "%zu ground px (%zu penumbra): max |V - box filter of the texture| %.2e, max |V - exact| "
      "%.3f texel/kernel widths\n",
      n, penumbra, worst_filter, worst_edge);
  ASSERT_GT(penumbra, 1000u);
  EXPECT_LT(worst_filter, 1.0 / texels);
  EXPECT_LE(worst_edge, 1.0);
}

// Two plates at different heights, in different slices, whose penumbrae
// overlap on the ground. There V lies between 1 − a − b (sum: the parts of
// the light they hide do not overlap) and 1 − max(a, b) (max: one hides
// what the other does); the product (1 − a)(1 − b) takes the hidden parts
// as independent, and comes closest to the reference.
TEST(OcclusionTextures, ProbabilisticCombinationBeatsSumAndMaxWhereOccludersOverlap) {
  TempDir dir;
  const std::vector<Plate> plates = overlapping_plates();
  const double size = kOverlapLightSize;
  const auto out = run_config(
      occlusion_experiment(
          json::array({plate_scene(write_plates(dir.path, plates, kOverlapEye), size)}),
          json::array(
              {occlusion_textures({{"combine", json::array({"probabilistic", "sum", "max"})}})}),
          256, 160, 120),
      "occlusion_overlap", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 3) << out.records.at(0).value("reason", "");
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  const ImageF ref = out.reference_visibility();
  std::vector<bool> overlap(ground.size(), false);
  size_t count = 0;
  for (size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) continue;
    const double x = positions.data[i * 4], z = positions.data[i * 4 + 2];
    const double a = 1.0 - exact_visibility(plates[0], x, z, size);
    const double b = 1.0 - exact_visibility(plates[1], x, z, size);
    // Both hide a clear part of the light, and the truth is not umbra.
    overlap[i] = a > 0.1 && b > 0.1 && ref.data[i] > 0.05f;
    count += overlap[i];
  }
  ASSERT_GT(count, 200u);
  std::vector<double> mean_abs;
  for (const std::string combine : {"probabilistic", "sum", "max"}) {
    const ImageF v = out.visibility("occlusion_textures/combine=" + combine);
    double sum_abs = 0.0, sum_signed = 0.0;
    for (size_t i = 0; i < ground.size(); ++i) {
      if (!overlap[i]) continue;
      const double err = double(v.data[i]) - double(ref.data[i]);
      sum_abs += std::abs(err);
      sum_signed += err;
    }
    mean_abs.push_back(sum_abs / double(count));
    std::printf("%s: %zu overlap px, mean |error| %.4f, mean signed %.4f\n", combine.c_str(), count,
                mean_abs.back(), sum_signed / double(count));
  }
  EXPECT_LT(mean_abs[0], mean_abs[1]);
  EXPECT_LT(mean_abs[0], mean_abs[2]);
}

// A thin plate slopes down to +x across four slices (25°, 1.0 to 1.8
// above the ground), under a light 1.5 wide. Each slice holds a strip of
// it, read through one plane of the slice; a shadow ray that rises towards
// +x crosses the plane of slice k + 1 beside the strip of slice k and the
// plane of slice k beside the strip of slice k + 1, and slips through
// between them, though the plate stops it. The paper's fix (§3.4, light
// leaks) projects each slice's texture onto the next one farther from the
// light, which then holds both strips and stops that ray: the leak in the
// plate's shadow on the ground shrinks, against the ray-traced reference.
// Its copy lies behind the surface it comes from, so the plate's lit face,
// which reads only the slices in front of it, is not darkened by it.
// Marking the slice towards the light instead (this project's earlier fix)
// puts the plate's copy into the slice its lit face fades in: that face
// darkens.
TEST(OcclusionTextures, ThePapersThinOccluderFixStopsRaysSlippingBetweenSlicesAndSparesLitFaces) {
  TempDir dir;
  const double size = 1.5;
  const glm::vec3 centre(-0.5f, 1.4f, 0.0f);
  const float angle = glm::radians(-25.0f);
  const glm::vec3 half(1.0f, 5e-3f, 0.6f);
  Mesh slope = make_box("slope", glm::vec3(0.0f), half);
  const glm::mat4 place =
      glm::rotate(glm::translate(glm::mat4(1.0f), centre), angle, glm::vec3(0.0f, 0.0f, 1.0f));
  transform_mesh(slope, place);
  const auto out = run_config(
      occlusion_experiment(
          json::array({plate_scene(write_plates(dir.path, {}, {1.5f, 4.0f, 3.0f}, {slope}), size)}),
          json::array({occlusion_textures(
              {{"slices", 4}, {"thin_occluder_fix", json::array({false, true})}})}),
          64, 160, 120),
      "occlusion_thin", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 2) << out.records.at(0).value("reason", "");
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  const ImageF ref = out.reference_visibility();
  const glm::mat4 to_slope = glm::inverse(place);
  std::vector<double> shadow_err, face_err;
  for (const std::string fix : {"false", "true"}) {
    const ImageF v = out.visibility("occlusion_textures/slices=4,thin_occluder_fix=" + fix);
    double shadow = 0.0, face = 0.0;
    size_t n_shadow = 0, n_face = 0;
    for (size_t i = 0; i < v.data.size(); ++i) {
      const float* p = &positions.data[i * 4];
      if (p[3] == 0.0f) continue;
      const double err = double(v.data[i]) - double(ref.data[i]);
      if (ground[i] && ref.data[i] < 0.5f) {  // the plate's shadow on the ground
        shadow += err;
        ++n_shadow;
      }
      const glm::vec3 local = glm::vec3(to_slope * glm::vec4(p[0], p[1], p[2], 1.0f));
      if (std::abs(local.y - half.y) < 1e-3f && std::abs(local.x) < 0.9f * half.x &&
          std::abs(local.z) < 0.9f * half.z) {  // the plate's lit face
        face += std::abs(err);
        ++n_face;
      }
    }
    ASSERT_GT(n_shadow, 300u);
    ASSERT_GT(n_face, 300u);
    shadow_err.push_back(shadow / double(n_shadow));
    face_err.push_back(face / double(n_face));
    std::printf(
        "thin_occluder_fix=%s: %zu shadow px on the ground, mean V - reference %+.4f; %zu px on "
        "the "
        "lit face, mean |V - reference| %.4f\n",
        fix.c_str(), n_shadow, shadow_err.back(), n_face, face_err.back());
  }
  EXPECT_GT(shadow_err[0], 0.1) << "no leak to stop: the scene does not provoke it";
  EXPECT_LT(std::abs(shadow_err[1]), 0.5 * shadow_err[0]);
  EXPECT_LT(face_err[1], 0.01) << "the fix darkens the plate's lit face";
}

// V of the job whose technique has `param` = `value`.
ImageF visibility_where(const RunOutput& out, const std::string& param, const std::string& value) {
  for (const json& r : out.records)
    if (r["technique"]["params"].value(param, "") == value) return out.image(r, "visibility");
  throw std::runtime_error("no job with " + param + "=" + value);
}

// Runs occlusion_textures with `params` over the plates under a light of
// side `size`, with a 4-spp reference (the tests that use it compare with
// closed forms), writing the G-buffer.
RunOutput run_on_plates(const std::vector<Plate>& plates, float size, const glm::vec3& eye,
                        const json& params, int width, int height, const std::string& name) {
  TempDir dir;
  return run_config(
      occlusion_experiment(json::array({plate_scene(write_plates(dir.path, plates, eye), size)}),
                           json::array({occlusion_textures(params)}), 4, width, height),
      name, gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
}

// The slicing the technique fits to these plates.
occlusion_texture::Slicing plate_slicing(const std::vector<Plate>& plates, float light_size,
                                         int slices) {
  Scene scene;
  scene.light = plate_light(light_size);
  for (const Plate& p : plates)
    scene.meshes.push_back(
        make_box("plate", {0.5f * (p.x0 + p.x1), p.h, 0.5f * (p.z0 + p.z1)},
                 {0.5f * (p.x1 - p.x0), p.half_thickness, 0.5f * (p.z1 - p.z0)}));
  return occlusion_texture::fit_slicing(scene, slices, occlusion_texture::Projection::Central);
}

// A high plate (off to the side, its shadow off the picture) and a low one
// whose top face lies on the far plane of the last of four slices (the
// slices end a hair below its bottom face). The paper reads each slice
// through its far plane, which is where this plate is: its penumbra on the
// ground (more than a slice below it) is then the exact one, up to the
// texels; read through the slice's middle, the plate is lifted by half a
// slice and its penumbra widens.
TEST(OcclusionTextures, TheFarPlaneLookupGivesTheExactPenumbraOfAPlateOnItsSlicesFarPlane) {
  const Plate high{1.2f, 1.5f, -1.5f, -1.2f, 2.2f, 1e-3f};
  const Plate low{-1.0f, 0.2f, -0.6f, 0.6f, 1.0f, 1e-3f};
  const float size = 1.0f;
  const auto out = run_on_plates({high, low}, size, {0.0f, 4.0f, 3.0f},
                                 {{"size", 1024},
                                  {"slices", 4},
                                  {"self_slab", "skip"},
                                  {"lookup_plane", json::array({"far", "mid"})}},
                                 160, 120, "occlusion_far_plane");
  ASSERT_EQ(out.summary.ok, 2) << out.records.at(0).value("reason", "");
  const occlusion_texture::Slicing slicing = plate_slicing({high, low}, size, 4);
  const float low_top_depth = kLightHeight - (low.h + low.half_thickness);
  ASSERT_NEAR(slicing.far_plane(3), low_top_depth, 0.02f * slicing.thickness)
      << "the low plate is not on the last slice's far plane";
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  std::vector<double> mean_abs;
  for (const std::string plane : {"far", "mid"}) {
    const ImageF v = visibility_where(out, "lookup_plane", plane);
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < ground.size(); ++i) {
      if (!ground[i]) continue;
      const double x = positions.data[i * 4], z = positions.data[i * 4 + 2];
      if (exact_visibility(high, x, z, size) < 1.0) continue;
      const double exact = exact_visibility(low, x, z, size);
      if (!(exact > 0.0 && exact < 1.0)) continue;  // the low plate's penumbra
      sum += std::abs(double(v.data[i]) - exact);
      ++n;
    }
    ASSERT_GT(n, 500u);
    mean_abs.push_back(sum / double(n));
    std::printf("lookup_plane=%s: %zu penumbra px, mean |V - exact| %.4f\n", plane.c_str(), n,
                mean_abs.back());
  }
  EXPECT_LT(mean_abs[0], 0.01);
  EXPECT_GT(mean_abs[1], 3.0 * mean_abs[0]) << "the middle plane should be visibly off";
}

// The paper drops the slice that holds a point for every point, receivers
// included (no caster/receiver split). A plate lies 0.4 above the ground, in
// the last of four slices about 0.62 thick (a second plate near the light
// stretches them): with the offset of one slice the ground under it counts
// that slice only over the 0.4 it lies beyond it, so V in the plate's
// umbra is 1 − 0.4 / t (the rule's closed form; the truth is 0). The
// receiver-aware rule reads the ground's own depth: V = 0. The camera looks
// in under the plate.
TEST(OcclusionTextures, TheSkipRuleFadesTheSliceInFrontOfAReceiverAsItDoesForACaster) {
  const Plate high{2.6f, 3.0f, -2.4f, -2.0f, 2.9f, 1e-3f};
  const Plate low{-1.0f, 0.2f, -0.6f, 0.6f, 0.4f, 1e-3f};
  const float size = 1.0f;
  const auto out =
      run_on_plates({high, low}, size, {0.0f, 1.5f, 4.0f},
                    {{"slices", 4}, {"self_slab", json::array({"skip", "receiver_aware"})}}, 320,
                    240, "occlusion_self_slab");
  ASSERT_EQ(out.summary.ok, 2) << out.records.at(0).value("reason", "");
  const occlusion_texture::Slicing slicing = plate_slicing({high, low}, size, 4);
  const double weight = (double(kLightHeight) - double(slicing.far_plane(3))) / slicing.thickness;
  ASSERT_GT(weight, 0.1);
  ASSERT_LT(weight, 0.9);
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  for (const std::string rule : {"skip", "receiver_aware"}) {
    const ImageF v = visibility_where(out, "self_slab", rule);
    double sum = 0.0, worst = 0.0;
    size_t n = 0;
    const double expected = rule == "skip" ? 1.0 - weight : 0.0;
    for (size_t i = 0; i < ground.size(); ++i) {
      if (!ground[i]) continue;
      const double x = positions.data[i * 4], z = positions.data[i * 4 + 2];
      if (exact_visibility(high, x, z, size) < 1.0) continue;
      // Deep in the umbra: the kernel lies inside the plate's texture.
      if (x < low.x0 + 0.3 || x > low.x1 - 0.3 || z < low.z0 + 0.3 || z > low.z1 - 0.3) continue;
      sum += v.data[i];
      worst = std::max(worst, std::abs(double(v.data[i]) - expected));
      ++n;
    }
    std::printf("self_slab=%s: %zu umbra px, mean V %.4f (closed form %.4f), max |V - it| %.2e\n",
                rule.c_str(), n, sum / double(n), expected, worst);
    ASSERT_GT(n, 300u);
    EXPECT_LT(worst, 1e-3) << rule;
  }
}

// Lights from 1e-4 to 20 times the sphere grid's extent (a kernel far
// larger than the texture, and 16² textures), and 4 to 16 slices whose
// boundaries cross every sphere: each V is finite and in [0, 1] (the
// harness fails a job whose V is not), and the tiny light gives the hard
// shadow.
TEST(OcclusionTextures, VisibilityStaysFiniteAtExtremeLightSizesAndOnSliceBoundaries) {
  const json techniques = json::array(
      {occlusion_textures({{"slices", json::array({4, 8, 16})},
                           {"filter", json::array({"mipmap", "nbuffers", "sat"})}}),
       occlusion_textures({{"size", 16}, {"filter", json::array({"mipmap", "nbuffers", "sat"})}})});
  for (const double light : {1e-4, 250.0}) {
    const auto out =
        run_config(occlusion_experiment(json::array({small_scene(light)}), techniques, 16, 64, 48),
                   "occlusion_extremes");
    EXPECT_EQ(out.summary.ok, 12) << "light " << light;
    for (const auto& r : out.records) {
      EXPECT_EQ(r["status"], "ok") << r.dump();
      EXPECT_EQ(r["metrics"]["visibility"]["all"]["nonfinite_count"], 0) << r.dump();
    }
    if (light < 1.0) {
      const ImageF ref = out.reference_visibility();
      const ImageF v = out.visibility("occlusion_textures/slices=16,filter=sat");
      size_t differ = 0;
      for (size_t i = 0; i < v.data.size(); ++i) differ += std::abs(v.data[i] - ref.data[i]) > 0.5f;
      EXPECT_LT(double(differ), 0.02 * double(v.data.size()));
    }
  }
}

}  // namespace
}  // namespace sb::test
