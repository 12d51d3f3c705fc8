// The kit's GLSL pieces (common/glsl_pcss.h, glsl_pcf.h,
// glsl_rotation_noise.h) run alone on a hand-made depth map, against
// analytic answers: a blocker half-plane at a known view depth, a half-lit
// step for the PCF, the similar-triangles penumbra drawn as rays, and
// interleaved gradient noise's closed form. pcss and pcf_jitter are these
// pieces composed (techniques/shadow_map/pcss.cpp, pcf_jitter.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/blue_noise.h"
#include "common/depth_pass.h"
#include "common/glsl_pcf.h"
#include "common/glsl_pcss.h"
#include "common/glsl_rotation_noise.h"
#include "common/sample_disks.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques {
namespace {

constexpr int kMap = 64;  // texels per side; columns < kEdge are the blocker
constexpr int kEdge = 32;
constexpr int kPixels = 8;  // the result target's side
constexpr float kNear = 1.0f, kFar = 10.0f;
constexpr float kBlockerViewDepth = 4.0f;

// The window depth a perspective map stores at view depth z (n = 1, f = 10).
float window_depth(float z) { return (kFar - kNear * kFar / z) / (kFar - kNear); }

// What the map lookup provides (common/map_lookup.h), no more: the two
// samplers, shadow_tap against the receiver's plane, and view_depth.
const char* const kHead = R"(#version 450 core
layout(binding = 1) uniform sampler2DShadow shadow_map;
layout(binding = 3) uniform sampler2D depth_map;
vec2 receiver_gradient = vec2(0.0);
float shadow_tap(vec3 t, vec2 offset) {
  return texture(shadow_map, vec3(t.xy + offset, min(t.z + dot(receiver_gradient, offset), 1.0)));
}
)";

// The test's inputs, after the kit's GLSL (which defines MAX_DISK_TAPS).
const char* const kInputs = R"(
uniform vec3 t;
uniform int half_side;
uniform float size_uv;
uniform float turns;
uniform int count;
uniform vec2 disk[MAX_DISK_TAPS];
uniform vec4 args;
layout(binding = 5) uniform sampler2D noise_mask;
out vec4 result;
// PCSS as techniques/shadow_map/pcss.cpp composes the pieces: search over
// the derived width, no blocker -> lit, else a PCF of RADIUS half the
// penumbra's width (args: light side, receiver view depth, tan_half_fov).
float pcss_composed(vec3 t, int search_half, int filter_half) {
  float search_uv = pcss_search_width_uv(args.x, args.y, light_depth_range.x, args.z);
  vec2 blockers = blocker_search_grid(t, search_half, search_uv);
  if (blockers.y == 0.0) return 1.0;
  float width_uv = penumbra_width_uv(args.x, args.y, blockers.x, args.z);
  return pcf_grid_radius(t, filter_half, 0.5 * width_uv);
}
)";

class KitGlsl : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gl::create_context(gl::Backend::OSMesa);
    target_ = gl::make_texture_2d(GL_RGBA32F, kPixels, kPixels);
    framebuffer_ = gl::make_framebuffer({target_.get()}, 0);
    map_ = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, kMap, kMap);
    std::vector<float> depths;
    for (int y = 0; y < kMap; ++y)
      for (int x = 0; x < kMap; ++x)
        depths.push_back(x < kEdge ? window_depth(kBlockerViewDepth) : 1.0f);
    glTextureSubImage2D(map_.get(), 0, 0, 0, kMap, kMap, GL_DEPTH_COMPONENT, GL_FLOAT,
                        depths.data());
    compare_ = gl::make_sampler(/*linear=*/false, /*compare=*/true, 1.0f);
    raw_ = gl::make_sampler(/*linear=*/false, /*compare=*/false, 1.0f);
  }

  // result = vec4(expression) in every pixel, uniforms set by `set`.
  template <typename F>
  std::vector<glm::vec4> eval(const std::string& expression, F set) {
    gl::Program program(
        "kit_glsl_test",
        {gl::kFullscreenVertexShader, "",
         std::string(kHead) + kLightDepthGlsl + kPcfGlsl + kPcssGlsl + kRotationNoiseGlsl +
             kBlueNoiseGlsl + kInputs + "void main() { result = vec4(" + expression + "); }\n"});
    program.set_if_active("light_depth_range", glm::vec2(kNear, kFar));
    set(program);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, kPixels, kPixels);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    program.use();
    glBindTextureUnit(1, map_.get());
    glBindSampler(1, compare_.get());
    glBindTextureUnit(3, map_.get());
    glBindSampler(3, raw_.get());
    gl::draw_fullscreen_triangle();
    std::vector<glm::vec4> out(size_t(kPixels * kPixels));
    glGetTextureImage(target_.get(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(glm::vec4)),
                      out.data());
    glBindSampler(1, 0);
    glBindSampler(3, 0);
    gl::throw_if_errors("kit glsl test");
    return out;
  }

  std::unique_ptr<gl::Context> context_;
  gl::Texture target_, map_;
  gl::Framebuffer framebuffer_;
  gl::Sampler compare_, raw_;
};

constexpr float kTexel = 1.0f / float(kMap);
// The centre of the first unblocked column, half-way up; the receiver lies
// between the blocker (window depth ~0.83) and the far background (1).
const glm::vec3 kAtEdge((float(kEdge) + 0.5f) * kTexel, 0.5f + 0.5f * kTexel, 0.95f);

// Taps one texel apart (search WIDTH 2·h texels), centred on the first lit
// column: h of the 2h+1 columns are the blocker, at view depth 4.
TEST_F(KitGlsl, BlockerSearchGridFindsTheBlockerPlanesDepthAndCount) {
  for (int h : {1, 2, 4}) {
    const glm::vec4 r =
        eval("blocker_search_grid(t, half_side, size_uv), 0.0, 0.0", [&](const gl::Program& p) {
          p.set("t", kAtEdge);
          p.set("half_side", h);
          p.set("size_uv", 2.0f * float(h) * kTexel);
        })[0];
    EXPECT_NEAR(r.x, kBlockerViewDepth, 1e-4) << "h " << h;
    EXPECT_EQ(r.y, float(h * (2 * h + 1))) << "h " << h;
  }
  // A receiver in front of the blocker has none: (0, 0).
  const glm::vec4 none =
      eval("blocker_search_grid(t, 2, 4.0 / 64.0), 0.0, 0.0",
           [&](const gl::Program& p) { p.set("t", glm::vec3(kAtEdge.x, kAtEdge.y, 0.5f)); })[0];
  EXPECT_EQ(none.x, 0.0f);
  EXPECT_EQ(none.y, 0.0f);
}

// Three taps on a line, radius 2 texels: unrotated, two fall on the blocker
// (x − 2, x − 1 texels); half a turn mirrors them, leaving one.
TEST_F(KitGlsl, BlockerSearchDiskCountsTheRotatedTapsOnTheBlocker) {
  const std::vector<glm::vec2> disk = {{-1.0f, 0.0f}, {-0.5f, 0.0f}, {1.0f, 0.0f}};
  for (const std::pair<float, float>& c : {std::pair{0.0f, 2.0f}, std::pair{0.5f, 1.0f}}) {
    const float turns = c.first, expected = c.second;
    const glm::vec4 r = eval(
        "blocker_search_disk(t, disk, count, rotation_by_turns(turns), vec2(size_uv)), 0.0, 0.0",
        [&](const gl::Program& p) {
          p.set("t", kAtEdge);
          p.set("disk", disk);
          p.set("count", 3);
          p.set("turns", turns);
          p.set("size_uv", 2.0f * kTexel);
        })[0];
    EXPECT_EQ(r.y, expected) << "turns " << turns;
    EXPECT_NEAR(r.x, kBlockerViewDepth, 1e-4) << "turns " << turns;
  }
}

// x where the line through (x0, 0) and (xb, zb) reaches depth z.
double ray_x(double x0, double xb, double zb, double z) { return x0 + (xb - x0) * z / zb; }

// The penumbra: rays from the light's two edges (±L/2 at depth 0) past a
// blocker edge at (0, z_b) land on the receiver plane z_r; their distance
// apart, over the map's 2·z_r·tan(fov/2) world units per uv, is the WIDTH.
// The search: rays from the light's edges to the receiving point (0, z_r)
// cross the near plane that far apart.
TEST_F(KitGlsl, PenumbraAndSearchWidthsAreTheSimilarTriangles) {
  const double tan_half_fov = 0.4;
  for (const glm::dvec3& c :
       {glm::dvec3(2.0, 8.0, 4.0), glm::dvec3(0.5, 6.0, 5.5), glm::dvec3(3.0, 9.0, 1.5)}) {
    const double light = c.x, zr = c.y, zb = c.z;
    const glm::vec4 r = eval(
        "penumbra_width_uv(args.x, args.y, args.z, args.w), "
        "pcss_search_width_uv(args.x, args.y, 1.0, args.w), "
        "penumbra_width_uv(args.x, args.z, args.y, args.w), 0.0",
        [&](const gl::Program& p) {
          p.set("args", glm::vec4(float(light), float(zr), float(zb), float(tan_half_fov)));
        })[0];
    const double penumbra =
        std::fabs(ray_x(light / 2, 0.0, zb, zr) - ray_x(-light / 2, 0.0, zb, zr));
    const double search =
        std::fabs(ray_x(light / 2, 0.0, zr, kNear) - ray_x(-light / 2, 0.0, zr, kNear));
    EXPECT_NEAR(r.x, penumbra / (2.0 * zr * tan_half_fov), 1e-5) << zr << " " << zb;
    EXPECT_NEAR(r.y, search / (2.0 * kNear * tan_half_fov), 1e-5) << zr << " " << zb;
    EXPECT_EQ(r.z, 0.0f) << "a blocker behind the receiver casts no penumbra";
  }
}

// A half-lit step: centred on the first lit column, h + 1 of the 2h + 1
// columns are lit; one column to the left, h. The same kernel given by its
// RADIUS h texels agrees.
TEST_F(KitGlsl, PcfGridOverAStepReturnsTheLitColumnsFraction) {
  for (int h : {0, 1, 2, 3}) {
    for (const std::pair<int, int>& c : {std::pair{0, h + 1}, std::pair{-1, h}}) {
      const int dx = c.first, lit = c.second;
      const glm::vec4 r = eval(
          "pcf_grid(t, half_side, vec2(size_uv)), "
          "pcf_grid_radius(t, half_side, float(half_side) * size_uv), 0.0, 0.0",
          [&](const gl::Program& p) {
            p.set("t", kAtEdge + glm::vec3(float(dx) * kTexel, 0.0f, 0.0f));
            p.set("half_side", h);
            p.set("size_uv", kTexel);
          })[0];
      EXPECT_FLOAT_EQ(r.x, float(lit) / float(2 * h + 1)) << "h " << h << ", dx " << dx;
      EXPECT_FLOAT_EQ(r.y, float(lit) / float(2 * h + 1)) << "h " << h << ", dx " << dx;
    }
  }
}

// A Poisson disk of radius 5 texels over the step: the fraction of taps
// that land on lit columns, counted on the CPU; quarter-turn rotation swaps
// x for −y, which the CPU count follows.
TEST_F(KitGlsl, PcfDiskReturnsTheFractionOfTapsOnLitTexels) {
  const std::vector<glm::vec2> disk = poisson_disk(24, 3);
  const float radius = 5.0f * kTexel;
  for (const float turns : {0.0f, 0.25f}) {
    int lit = 0;
    for (const glm::vec2& d : disk) {
      const float x = turns == 0.0f ? d.x : -d.y;
      lit += int(std::floor((kAtEdge.x + x * radius) * float(kMap))) >= kEdge;
    }
    const glm::vec4 r = eval(
        "pcf_disk(t, disk, count, rotation_by_turns(turns), vec2(size_uv)), "
        "pcf_disk_sum(t, disk, 4, count, rotation_by_turns(turns), vec2(size_uv)), 0.0, 0.0",
        [&](const gl::Program& p) {
          p.set("t", kAtEdge);
          p.set("disk", disk);
          p.set("count", int(disk.size()));
          p.set("turns", turns);
          p.set("size_uv", radius);
        })[0];
    EXPECT_FLOAT_EQ(r.x, float(lit) / float(disk.size())) << "turns " << turns;
    EXPECT_GT(lit, 0);
    EXPECT_LT(lit, int(disk.size()));
    int lit_after_4 = 0;
    for (size_t i = 4; i < disk.size(); ++i) {
      const float x = turns == 0.0f ? disk[i].x : -disk[i].y;
      lit_after_4 += int(std::floor((kAtEdge.x + x * radius) * float(kMap))) >= kEdge;
    }
    EXPECT_EQ(r.y, float(lit_after_4)) << "turns " << turns;
  }
}

// The columns (of the map's kMap) that 2h+1 taps `step` texels apart,
// centred on column coordinate x, land in; fails the test if a tap lies
// within 1e-3 texel of a column boundary, where float rounding may decide.
std::vector<int> tap_columns(double x, int h, double step) {
  std::vector<int> columns;
  for (int i = -h; i <= h; ++i) {
    const double c = x + i * step;
    EXPECT_GT(std::fabs(c - std::round(c)), 1e-3) << "tap at column " << c;
    columns.push_back(int(std::floor(c)));
  }
  return columns;
}

// PCSS composed from the pieces, against Fernando's recipe evaluated on
// the CPU from the formulas alone: a receiver at view depth 8 beside the
// blocker half-plane (view depth 4), n = 1, tan_half_fov 0.5. Search width
// L·(z_r − n)/(z_r·2n·tan), grid taps (width/2)/h apart; penumbra width
// L·(z_r − z_b)/(z_b·2·z_r·tan); PCF taps (width/4)/h apart (radius width/2).
TEST_F(KitGlsl, PcssComposedFromThePiecesIsFernandosRecipe) {
  const double tan_half_fov = 0.5, zr = 8.0, x = double(kEdge) + 0.15;
  struct Case {
    double light;
    int search_half, filter_half;
  };
  for (const Case& c : {Case{0.1, 2, 4}, Case{0.3, 1, 4}, Case{0.3, 3, 2}, Case{0.6, 2, 3}}) {
    SCOPED_TRACE("L " + std::to_string(c.light) + ", search h " + std::to_string(c.search_half) +
                 ", filter h " + std::to_string(c.filter_half));
    const double search_texels = c.light * (zr - kNear) / (zr * 2.0 * kNear * tan_half_fov) * kMap;
    int blocker_columns = 0;
    for (int col : tap_columns(x, c.search_half, 0.5 * search_texels / std::max(c.search_half, 1)))
      blocker_columns += col < kEdge;
    ASSERT_GT(blocker_columns, 0);
    const double zb = kBlockerViewDepth;
    const double width_texels = c.light * (zr - zb) / (zb * 2.0 * zr * tan_half_fov) * kMap;
    int lit = 0;
    for (int col : tap_columns(x, c.filter_half, 0.5 * width_texels / std::max(c.filter_half, 1)))
      lit += col >= kEdge;
    const float expected = float(lit) / float(2 * c.filter_half + 1);
    const float light = float(c.light), search_half = float(c.search_half);
    const int search = c.search_half, filter = c.filter_half;
    const glm::vec4 r =
        eval("pcss_composed(t, half_side, count), 0.0, 0.0, 0.0", [&](const gl::Program& p) {
          p.set("t", glm::vec3(float(x) * kTexel, kAtEdge.y, window_depth(float(zr))));
          p.set("args", glm::vec4(light, float(zr), float(tan_half_fov), 0));
          p.set("half_side", search);
          p.set("count", filter);
        })[0];
    EXPECT_NEAR(r.x, expected, 1e-6)
        << "lit " << lit << " of " << 2 * filter + 1 << ", search_half " << search_half;
  }
  // A receiver in front of the blocker finds none: lit.
  const glm::vec4 r = eval("pcss_composed(t, 2, 2), 0.0, 0.0, 0.0", [&](const gl::Program& p) {
    p.set("t", glm::vec3(float(x) * kTexel, kAtEdge.y, window_depth(3.0f)));
    p.set("args", glm::vec4(0.3f, 3.0f, 0.5f, 0.0f));
  })[0];
  EXPECT_EQ(r.x, 1.0f);
}

// fract(52.9829189 · fract(0.06711056·x + 0.00583715·y)) at each pixel
// centre, in [0,1), and rotation_by_turns(0.25) turns (1, 0) to (0, 1).
TEST_F(KitGlsl, InterleavedGradientNoiseIsJimenezsFormulaAndRotationIsCounterClockwise) {
  const std::vector<glm::vec4> r =
      eval("interleaved_gradient_noise(gl_FragCoord.xy), rotation_by_turns(0.25) * vec2(1, 0), 0.0",
           [](const gl::Program&) {});
  for (int y = 0; y < kPixels; ++y)
    for (int x = 0; x < kPixels; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double inner = 0.06711056 * px + 0.00583715 * py;
      const double outer = 52.9829189 * (inner - std::floor(inner));
      const glm::vec4 v = r[size_t(y) * size_t(kPixels) + size_t(x)];
      EXPECT_NEAR(v.x, outer - std::floor(outer), 1e-4) << x << "," << y;
      EXPECT_GE(v.x, 0.0f);
      EXPECT_LT(v.x, 1.0f);
      EXPECT_NEAR(v.y, 0.0f, 1e-6);
      EXPECT_NEAR(v.z, 1.0f, 1e-6);
    }
}

// The blue-noise tile read at window pixels is the mask's value there, and
// the tile repeats: 16 pixels right and 32 up read the same texel.
TEST_F(KitGlsl, BlueNoiseReadsTheMaskRepeatedOverTheWindow) {
  const int side = 16;
  const std::vector<float> mask = blue_noise_mask(side, 2);
  const gl::Texture texture = make_blue_noise_texture(side, 2);
  const std::vector<glm::vec4> r = eval(
      "blue_noise(noise_mask, gl_FragCoord.xy), "
      "blue_noise(noise_mask, gl_FragCoord.xy + vec2(16.0, 32.0)), 0.0, 0.0",
      [&](const gl::Program&) { glBindTextureUnit(5, texture.get()); });
  glBindTextureUnit(5, 0);
  for (int y = 0; y < kPixels; ++y)
    for (int x = 0; x < kPixels; ++x) {
      const glm::vec4 v = r[size_t(y) * size_t(kPixels) + size_t(x)];
      EXPECT_EQ(v.x, mask[size_t(y) * size_t(side) + size_t(x)]) << x << "," << y;
      EXPECT_EQ(v.y, v.x) << x << "," << y;
    }
}

}  // namespace
}  // namespace sb::techniques
