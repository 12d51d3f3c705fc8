// ESM's lookup GLSL run alone on a small map of known depths, against a CPU
// evaluation of what the filtered exponential map means: the bilinear
// (GL_LINEAR, clamp-to-edge) average of exp(c·z) over the four nearest
// texels, divided by exp(c·z_receiver) and clamped to 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "common/separable_filter.h"
#include "filtered_map/filtered_map_variants.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques::filtered_map {
namespace {

constexpr int kMap = 4;       // texels per side
constexpr int kSamples = 32;  // lookups per side: 8 per texel, edges included

// Neighbouring texels differ by up to 0.7 in depth, where exp's geometric
// and arithmetic means differ by orders of magnitude.
float depth(int i, int j) {
  static const float kDepths[4] = {0.2f, 0.9f, 0.55f, 0.35f};
  return kDepths[(i + 2 * j + (i * j) % 3) % 4];
}

// The lookup's inputs as map_lookup.h provides them; t comes from the
// fragment's position, (x+½)/kSamples.
const char* const kHead = R"(#version 450 core
layout(binding = 4) uniform sampler2DArray moments;
uniform float receiver;
uniform float samples;
out float visibility;
float receiver_depth01() { return receiver; }
float clamp_unit(float v) { return clamp(v, 0.0, 1.0); }
)";

const char* const kMain = R"(
void main() { visibility = lit_fraction(vec3(gl_FragCoord.xy / samples, 0.5)); }
)";

// Σ w·exp(c·(z − z_r)) over GL_LINEAR's footprint at t, clamped to 1.
double expected_visibility(double tx, double ty, double c, double receiver) {
  const double px = tx * kMap - 0.5, py = ty * kMap - 0.5;
  const double x0 = std::floor(px), y0 = std::floor(py);
  const double fx = px - x0, fy = py - y0;
  const auto texel = [](double i) { return int(std::clamp(i, 0.0, double(kMap - 1))); };
  double sum = 0.0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double w = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
      const double z = depth(texel(x0 + dx), texel(y0 + dy));
      sum += w * std::exp(c * (z - receiver));
    }
  return std::min(sum, 1.0);
}

class EsmLookup : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gl::create_context(gl::Backend::OSMesa);
    target_ = gl::make_texture_2d(GL_R32F, kSamples, kSamples);
    framebuffer_ = gl::make_framebuffer({target_.get()}, 0);
  }

  // The map as the pipeline makes it (filtered_map.cpp): one R32F layer,
  // bilinear, clamped; `stored` gives each texel's value.
  template <typename F>
  gl::Texture map(F stored) const {
    gl::Texture t = make_array_texture(GL_R32F, kMap, 1);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    std::vector<float> texels;
    for (int j = 0; j < kMap; ++j)
      for (int i = 0; i < kMap; ++i) texels.push_back(stored(depth(i, j)));
    glTextureSubImage3D(t.get(), 0, 0, 0, 0, kMap, kMap, 1, GL_RED, GL_FLOAT, texels.data());
    return t;
  }

  std::vector<float> run(bool log_space, float c, float receiver, const gl::Texture& moments) {
    const BasisShader shader = esm_shader(log_space, c);
    gl::Program program("esm_lookup_test", {gl::kFullscreenVertexShader, "",
                                            kHead + shader.lit_fraction_glsl + kMain});
    program.set("exponent", c);
    program.set("receiver", receiver);
    program.set("samples", float(kSamples));
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, kSamples, kSamples);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    program.use();
    glBindTextureUnit(4, moments.get());
    gl::draw_fullscreen_triangle();
    std::vector<float> out(size_t(kSamples * kSamples));
    glGetTextureImage(target_.get(), 0, GL_RED, GL_FLOAT, GLsizei(out.size() * sizeof(float)),
                      out.data());
    gl::throw_if_errors("esm lookup test");
    return out;
  }

  // Largest |V − expected| over the kSamples² lookups.
  double worst_error(const std::vector<float>& v, float c, float receiver) const {
    double worst = 0.0;
    for (int y = 0; y < kSamples; ++y)
      for (int x = 0; x < kSamples; ++x) {
        const double e =
            expected_visibility((x + 0.5) / kSamples, (y + 0.5) / kSamples, c, receiver);
        worst = std::max(worst, std::fabs(double(v[size_t(y) * size_t(kSamples) + size_t(x)]) - e));
      }
    return worst;
  }

  std::unique_ptr<gl::Context> context_;
  gl::Texture target_;
  gl::Framebuffer framebuffer_;
};

// Receivers at 0.6 see the 0.9 texels' light leak (V = 1 near them), those
// just behind the deepest occluder get soft values everywhere.
std::vector<float> receivers(float c) { return {0.6f, 0.9f + 1.0f / c, 0.9f + 2.0f / c}; }

std::string scientific(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2e", v);
  return text;
}

// The map and receivers give soft values (0 < V < 1) in many lookups, where
// averaging depths instead of exponentials shows.
TEST(EsmLookupSetup, ManyLookupsArePartlyLit) {
  for (float c : {20.0f, 80.0f, 200.0f})
    for (float receiver : {0.9f + 1.0f / c, 0.9f + 2.0f / c}) {
      int soft = 0;
      for (int y = 0; y < kSamples; ++y)
        for (int x = 0; x < kSamples; ++x) {
          const double v =
              expected_visibility((x + 0.5) / kSamples, (y + 0.5) / kSamples, c, receiver);
          soft += v > 0.01 && v < 0.99;
        }
      EXPECT_GT(soft, kSamples * kSamples / 4) << "c = " << c << ", receiver " << receiver;
    }
}

// The default log-space map stores z: its lookup must still average exp(c·z).
TEST_F(EsmLookup, LogSpaceAveragesTheExponentialsNotTheDepths) {
  const gl::Texture moments = map([](float z) { return z; });
  for (float c : {20.0f, 80.0f, 200.0f})
    for (float receiver : receivers(c)) {
      const double e = worst_error(run(true, c, receiver, moments), c, receiver);
      EXPECT_LT(e, 1e-5) << "c = " << c << ", receiver " << receiver;
      RecordProperty("worst_error_c" + std::to_string(int(c)) + "_r" + std::to_string(receiver),
                     scientific(e));
    }
}

// The linear map stores exp(c·z) and lets GL_LINEAR average it: the same
// expectation holds, which checks the CPU model of GL_LINEAR above.
TEST_F(EsmLookup, LinearStorageMatchesTheSameExpectation) {
  for (float c : {20.0f, 80.0f}) {
    const gl::Texture moments = map([c](float z) { return std::exp(c * z); });
    for (float receiver : receivers(c)) {
      const double e = worst_error(run(false, c, receiver, moments), c, receiver);
      EXPECT_LT(e, 1e-4) << "c = " << c << ", receiver " << receiver;
      RecordProperty(
          "linear_worst_error_c" + std::to_string(int(c)) + "_r" + std::to_string(receiver),
          scientific(e));
    }
  }
}

}  // namespace
}  // namespace sb::techniques::filtered_map
