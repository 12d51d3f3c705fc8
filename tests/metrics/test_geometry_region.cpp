// metrics::geometry_mask and compare_within: the `geometry` region (measured
// surface pixels outside attached shadow) and its figures, against errors
// worked out by hand, and its independence from framing, which `all` lacks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "metrics/geometry_region.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"
#include "test_util.h"

namespace sb::metrics {

using core::AreaLight;
using core::ImageF;

namespace {

// A G-buffer drawn from a character map, one row per string, under the
// default light (a 1x1 rectangle at y = 10 over the origin):
//   's' sky; 'g' a floor at the origin facing up (the whole light above it);
//   'a' the floor facing down (attached shadow); 'c' a wall at the origin
//   facing +x (its tangent plane cuts the light: the horizon-cut band).
struct GBuffer {
  ImageF positions, normals;
};

GBuffer gbuffer(const std::vector<std::string>& rows) {
  const int h = static_cast<int>(rows.size()), w = static_cast<int>(rows[0].size());
  GBuffer g{ImageF(w, h, 4), ImageF(w, h, 3)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const char k = rows[static_cast<size_t>(y)][static_cast<size_t>(x)];
      if (k == 's') continue;
      g.positions.at(x, y, 3) = 1.0f;
      if (k == 'g') g.normals.at(x, y, 1) = 1.0f;
      if (k == 'a') g.normals.at(x, y, 1) = -1.0f;
      if (k == 'c') g.normals.at(x, y, 0) = 1.0f;
    }
  return g;
}

std::vector<LightHorizon> horizon_of(const GBuffer& g) {
  return classify_light_horizon(g.positions, g.normals, AreaLight{});
}

// `all` as the job executor measures it: every pixel but the horizon-cut
// band, whose values are the reference's first.
ErrorStats all_region(const ImageF& test, const ImageF& ref,
                      const std::vector<LightHorizon>& horizon) {
  std::vector<uint8_t> measured = horizon_mask(horizon, LightHorizon::Cuts);
  for (auto& m : measured) m = m ? 0 : 1;
  ImageF t = test;
  for (size_t p = 0; p < measured.size(); ++p)
    if (!measured[p]) t.data[p] = ref.data[p];
  return compare(t, ref, &measured);
}

TEST(GeometryRegion, IsTheSurfaceOutsideAttachedShadowAndTheHorizonCutBand) {
  const GBuffer g = gbuffer({"sgga", "cgsg"});
  EXPECT_EQ(geometry_mask(horizon_of(g)), (std::vector<uint8_t>{0, 1, 1, 0, 0, 1, 0, 1}));
}

TEST(GeometryRegion, ErrorsOverTheRegionAreTheHandWorkedOnes) {
  // Geometry pixels (1,0), (2,0), (1,1): errors -0.5, 0, +0.25. The sky
  // (0,0) is wrong by 1 (a technique that broke V = 1 there), the cut pixel
  // (3,0) by 0.6; attached pixels are 0 on both sides.
  const GBuffer g = gbuffer({"sggc", "agsa"});
  ImageF ref(4, 2, 1), test(4, 2, 1);
  const float r[8] = {1, 0.75f, 1, 0.3f, 0, 0.5f, 1, 0};
  const float t[8] = {0, 0.25f, 1, 0.9f, 0, 0.75f, 1, 0};
  for (size_t i = 0; i < 8; ++i) {
    ref.data[i] = r[i];
    test.data[i] = t[i];
  }
  const ErrorStats s = compare_within(test, ref, geometry_mask(horizon_of(g)));
  const double rmse = std::sqrt((0.25 + 0.0625) / 3.0);
  EXPECT_EQ(s.pixel_count, 3u);
  EXPECT_DOUBLE_EQ(s.rmse, rmse);
  EXPECT_DOUBLE_EQ(s.mae, 0.75 / 3.0);
  EXPECT_DOUBLE_EQ(s.mean_signed, -0.25 / 3.0);
  EXPECT_DOUBLE_EQ(s.psnr, 20.0 * std::log10(1.0 / rmse));
  EXPECT_EQ(s.max_error, 0.5);
  EXPECT_EQ(s.max_x, 1);
  EXPECT_EQ(s.max_y, 0);
  EXPECT_DOUBLE_EQ(s.frac_over_01, 2.0 / 3.0);
  EXPECT_TRUE(std::isnan(s.ssim)) << "an image under 11x11 has no SSIM";
  // `all` keeps the sky and the attached pixels: 7 pixels, the sky's error.
  const ErrorStats all = all_region(test, ref, horizon_of(g));
  EXPECT_EQ(all.pixel_count, 7u);
  EXPECT_DOUBLE_EQ(all.rmse, std::sqrt((0.25 + 0.0625 + 1.0) / 7.0));
}

// A block of surface (floor, some attached pixels, a horizon-cut column)
// with a technique's error in it, framed by `left`/`top` sky columns/rows and
// `right`/`bottom` more: the same scene with more or less sky around it.
struct Framed {
  GBuffer g;
  ImageF test, ref;
};

Framed framed(int left, int top, int right, int bottom) {
  constexpr int kW = 24, kH = 20;
  const ImageF truth = test::pattern_image(kW, kH, 1);
  const ImageF guess = test::blur_shift(truth, 2, 1);
  const int w = left + kW + right, h = top + kH + bottom;
  std::vector<std::string> rows(static_cast<size_t>(h), std::string(static_cast<size_t>(w), 's'));
  Framed f{{}, ImageF(w, h, 1, 1.0f), ImageF(w, h, 1, 1.0f)};  // V = 1 on the sky
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const char k = x == 17 ? 'c' : (x < 4 && y > 12) ? 'a' : 'g';
      rows.at(static_cast<size_t>(top) + static_cast<size_t>(y))
          .at(static_cast<size_t>(left) + static_cast<size_t>(x)) = k;
      const bool attached = k == 'a';
      f.ref.at(left + x, top + y) = attached ? 0.0f : truth.at(x, y);
      f.test.at(left + x, top + y) = attached ? 0.0f : guess.at(x, y);
    }
  f.g = gbuffer(rows);
  return f;
}

TEST(GeometryRegion, MoreSkyInTheFrameLeavesTheGeometryErrorUnchangedButNotAll) {
  // Six pixels of sky on every side, then 30 more columns and 25 more rows.
  const Framed tight = framed(6, 6, 6, 6), wide = framed(6, 31, 36, 6);
  const ErrorStats a = compare_within(tight.test, tight.ref, geometry_mask(horizon_of(tight.g)));
  const ErrorStats b = compare_within(wide.test, wide.ref, geometry_mask(horizon_of(wide.g)));
  ASSERT_GT(a.rmse, 0.01);
  EXPECT_EQ(a.pixel_count, 24u * 20u - 20u - 4u * 7u);
  EXPECT_EQ(a.pixel_count, b.pixel_count);
  EXPECT_EQ(a.rmse, b.rmse);
  EXPECT_EQ(a.mae, b.mae);
  EXPECT_EQ(a.max_error, b.max_error);
  EXPECT_EQ(a.psnr, b.psnr);
  EXPECT_EQ(a.frac_over_005, b.frac_over_005);
  EXPECT_NEAR(a.ssim, b.ssim, 1e-12);
  EXPECT_LT(a.ssim, 0.99);
  // The sky dilutes `all`: its RMSE scales by sqrt(pixels_tight / pixels_wide).
  const ErrorStats all_a = all_region(tight.test, tight.ref, horizon_of(tight.g));
  const ErrorStats all_b = all_region(wide.test, wide.ref, horizon_of(wide.g));
  EXPECT_GT(all_a.rmse, 1.5 * all_b.rmse);
  EXPECT_GT(all_b.ssim, all_a.ssim);
}

TEST(GeometryRegion, ATechniqueWrongOnTheSkyKeepsItsGeometryFiguresSsimIncluded) {
  // The sky is not the technique's to shade: wrong values there (V = 0.2
  // where the contract says 1) must not reach the region, nor its SSIM
  // windows that straddle the surface's edge.
  const Framed right = framed(6, 6, 6, 6);
  Framed wrong = right;
  for (size_t p = 0; p < wrong.test.data.size(); ++p)
    if (wrong.g.positions.data[p * 4 + 3] == 0.0f) wrong.test.data[p] = 0.2f;
  const std::vector<uint8_t> region = geometry_mask(horizon_of(right.g));
  const ErrorStats a = compare_within(right.test, right.ref, region);
  const ErrorStats b = compare_within(wrong.test, wrong.ref, region);
  EXPECT_EQ(a.rmse, b.rmse);
  EXPECT_EQ(a.ssim, b.ssim);
  // Averaging the plain SSIM map over the region, as the penumbra region
  // does, would let the sky in: the test above would see it.
  EXPECT_NE(compare(right.test, right.ref, &region).ssim,
            compare(wrong.test, wrong.ref, &region).ssim);
}

TEST(GeometryRegion, MatchesOutsideSaysWhenTheRegionCanShareTheOtherMasksSsimPass) {
  const Framed right = framed(6, 6, 6, 6);
  const std::vector<uint8_t> region = geometry_mask(horizon_of(right.g));
  // The cut column differs (the executor gives it the reference's values
  // before this test); the sky and attached pixels agree.
  Framed cut_from_ref = right;
  for (size_t p = 0; p < region.size(); ++p)
    if (right.g.positions.data[p * 4 + 3] != 0.0f && !region[p])
      cut_from_ref.test.data[p] = cut_from_ref.ref.data[p];
  EXPECT_FALSE(matches_outside(right.test, right.ref, region));
  ASSERT_TRUE(matches_outside(cut_from_ref.test, cut_from_ref.ref, region));
  const ErrorStats shared = compare(cut_from_ref.test, cut_from_ref.ref, &region);
  const ErrorStats own = compare_within(cut_from_ref.test, cut_from_ref.ref, region);
  EXPECT_EQ(shared.rmse, own.rmse);
  EXPECT_EQ(shared.ssim, own.ssim);
  // One sky pixel off by the least float step no longer matches.
  Framed speck = cut_from_ref;
  speck.test.data[0] = std::nextafter(1.0f, 0.0f);
  EXPECT_FALSE(matches_outside(speck.test, speck.ref, region));
}

}  // namespace
}  // namespace sb::metrics
