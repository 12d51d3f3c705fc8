// The light-shaped distance of the silhouette bands (common/silhouette_band.h)
// run alone on a grid of points, for a light whose projected axes are not
// orthogonal (a rectangle seen at a slant is a parallelogram). Truth: a
// point p = a + α·hu + β·hv lies in the parallelogram of half axes hu, hv
// about a grown by g iff max(|α|, |β|) ≤ g, so the distance from a point is
// max(|α|, |β|) in closed form; along a segment with a varying scale the
// least ratio is found on the CPU by dense sampling of the segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/silhouette_band.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques {
namespace {

constexpr int kGrid = 32;        // points per side
constexpr float kExtent = 2.5f;  // the grid spans ±kExtent light units

// A light seen at a slant: hu·hv = 0.6 (an angle of 50° between the axes).
const glm::vec2 kHu{1.0f, 0.0f}, kHv{0.6f, 0.5f};

const char* const kMain = R"(
uniform vec2 a, b, hu, hv;
uniform float sa, sb, extent, grid;
out float ratio;
void main() {
  // The fragment's point in the light's coordinates, then in the plane.
  vec2 ab = extent * (2.0 * gl_FragCoord.xy / grid - 1.0);
  vec2 p = a + ab.x * hu + ab.y * hv;
  float t;
  ratio = light_ratio(p, a, b, hu, hv, sa, sb, t);
}
)";

// (α, β) with v = α·hu + β·hv, by Cramer's rule.
glm::dvec2 coordinates(glm::dvec2 v, glm::dvec2 hu, glm::dvec2 hv) {
  const double det = hu.x * hv.y - hu.y * hv.x;
  return {(v.x * hv.y - v.y * hv.x) / det, (hu.x * v.y - hu.y * v.x) / det};
}

class LightFootprint : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gl::create_context(gl::Backend::OSMesa);
    target_ = gl::make_texture_2d(GL_R32F, kGrid, kGrid);
    framebuffer_ = gl::make_framebuffer({target_.get()}, 0);
    program_ = gl::Program("light_footprint_test", {gl::kFullscreenVertexShader, "",
                                                    std::string("#version 450 core\n") +
                                                        kSilhouetteBandFragmentGlsl + kMain});
  }

  // light_ratio at the kGrid² points a + α·hu + β·hv, α and β in ±kExtent.
  std::vector<float> run(glm::vec2 a, glm::vec2 b, float sa, float sb) {
    program_.use();
    program_.set("a", a);
    program_.set("b", b);
    program_.set("hu", kHu);
    program_.set("hv", kHv);
    program_.set("sa", sa);
    program_.set("sb", sb);
    program_.set("extent", kExtent);
    program_.set("grid", float(kGrid));
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, kGrid, kGrid);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gl::draw_fullscreen_triangle();
    std::vector<float> out(size_t(kGrid * kGrid));
    glGetTextureImage(target_.get(), 0, GL_RED, GL_FLOAT, GLsizei(out.size() * sizeof(float)),
                      out.data());
    gl::throw_if_errors("light footprint test");
    return out;
  }

  // The point of pixel (x, y) in the light's coordinates.
  static glm::dvec2 grid_coordinates(int x, int y) {
    return {kExtent * (2.0 * (x + 0.5) / kGrid - 1.0), kExtent * (2.0 * (y + 0.5) / kGrid - 1.0)};
  }

  std::unique_ptr<gl::Context> context_;
  gl::Texture target_;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
};

// From a single point (a = b, s = 1) the ratio is max(|α|, |β|): the
// parallelogram's corners a ± hu ± hv are at distance 1, as are its sides.
// Dot products with hu and hv (a rectangle's coordinates) read the corner
// a + hu + hv at 1.98 and a + hu − hv at 0.40 here.
TEST_F(LightFootprint, DistanceFromAPointIsTheParallelogramsGauge) {
  const glm::vec2 a{0.3f, -0.2f};
  const std::vector<float> ratio = run(a, a, 1.0f, 1.0f);
  double worst = 0.0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const glm::dvec2 c = grid_coordinates(x, y);
      const double expected = std::max(std::fabs(c.x), std::fabs(c.y));
      worst = std::max(worst, std::fabs(ratio[size_t(y) * size_t(kGrid) + size_t(x)] - expected));
    }
  EXPECT_LT(worst, 1e-4);
  RecordProperty("worst_error", std::to_string(worst));
}

// Along a slanted segment whose scale grows from 0.4 to 1.6, the least
// g(t)/s(t), against a CPU search over 20001 points of the segment.
TEST_F(LightFootprint, LeastRatioAlongASegmentMatchesADenseSearch) {
  const glm::vec2 a{-0.5f, -0.4f}, b{0.7f, 0.9f};
  const float sa = 0.4f, sb = 1.6f;
  const std::vector<float> ratio = run(a, b, sa, sb);
  double worst = 0.0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const glm::dvec2 g = grid_coordinates(x, y);
      const glm::dvec2 p = glm::dvec2(a) + g.x * glm::dvec2(kHu) + g.y * glm::dvec2(kHv);
      double least = 1e300;
      constexpr int kSteps = 20000;
      for (int i = 0; i <= kSteps; ++i) {
        const double t = double(i) / kSteps;
        const glm::dvec2 c = coordinates(p - glm::mix(glm::dvec2(a), glm::dvec2(b), t), kHu, kHv);
        least = std::min(least, std::max(std::fabs(c.x), std::fabs(c.y)) / (sa + t * (sb - sa)));
      }
      // The search's own step: g/s changes by at most ~|d(g/s)/dt| / kSteps.
      worst = std::max(
          worst, std::fabs(ratio[size_t(y) * size_t(kGrid) + size_t(x)] - least) / (1.0 + least));
    }
  EXPECT_LT(worst, 1e-3);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace
}  // namespace sb::techniques
