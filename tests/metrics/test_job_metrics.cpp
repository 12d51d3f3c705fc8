// metrics::measure, a job's figures as its record holds them: regional FLIP
// computed as regional SSIM is (geometry and terminator in isolation, the
// reference's values outside them), the terminator region (the pixels whose
// tangent plane cuts the light, which no other region holds) and the shaded
// image's whole-image FLIP, each against answers known without the code
// under test: identical pixels give FLIP 0 and SSIM 1, a constant
// difference d gives RMSE, MAE and mean_signed d.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "metrics/flip.h"
#include "metrics/geometry_region.h"
#include "metrics/job_metrics.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"
#include "metrics/regions.h"
#include "record/figures.h"

namespace sb::metrics {

using core::AreaLight;
using core::ImageF;

namespace {

// A 48x40 G-buffer under the default light (a 1x1 rectangle at y = 10 over
// the origin), by column: sky left of x = 8 ('s'); a floor facing up (the
// whole light above it, 'g'); a wall facing +x at the origin from x = 22 to
// 25, whose tangent plane cuts the light ('c'); the floor again; attached
// shadow (the floor facing down, 'a') from x = 40. With `cut` false the wall
// is floor too.
constexpr int kW = 48, kH = 40;

char kind(int x, bool cut) {
  if (x < 8) return 's';
  if (cut && x >= 22 && x < 26) return 'c';
  if (x >= 40) return 'a';
  return 'g';
}

// The regions as the job executor builds them (run/measurement_basis.cpp).
Regions regions_of(bool cut, const ImageF& ref_visibility) {
  ImageF positions(kW, kH, 4), normals(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const char k = kind(x, cut);
      if (k == 's') continue;
      positions.at(x, y, 3) = 1.0f;
      if (k == 'g') normals.at(x, y, 1) = 1.0f;
      if (k == 'a') normals.at(x, y, 1) = -1.0f;
      if (k == 'c') normals.at(x, y, 0) = 1.0f;
    }
  RegionInputs in;
  in.horizon = classify_light_horizon(positions, normals, AreaLight{});
  in.reference_penumbra = penumbra_mask(ref_visibility);
  in.receiver.assign(in.horizon.size(), 0);
  return make_regions(in);
}

// Every region of the catalogue, in its order, is made when the view has
// it: receivers and the distance thirds included.
TEST(JobMetrics, EveryRegionOfTheCatalogueHasItsMask) {
  ImageF positions(kW, kH, 4), normals(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      positions.at(x, y, 0) = float(x);
      positions.at(x, y, 3) = 1.0f;
      normals.at(x, y, 1) = 1.0f;
    }
  RegionInputs in;
  in.horizon = classify_light_horizon(positions, normals, AreaLight{});
  in.reference_penumbra.assign(in.horizon.size(), 1);
  in.receiver.assign(in.horizon.size(), 1);
  in.positions = &positions;
  in.distance_thirds = true;
  const Regions regions = make_regions(in);
  ASSERT_EQ(regions.masks.size(), record::regions().size());
  for (size_t i = 0; i < regions.masks.size(); ++i)
    EXPECT_EQ(regions.masks[i].key, record::regions()[i].key);
}

// The reference's V: 1 on the sky, 0 in attached shadow, a soft ramp across
// the floor, 0.3 on the wall.
ImageF reference_visibility(bool cut) {
  ImageF v(kW, kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const char k = kind(x, cut);
      v.at(x, y, 0) = k == 's'   ? 1.0f
                      : k == 'a' ? 0.0f
                      : k == 'c' ? 0.3f
                                 : 0.5f + 0.4f * std::sin(0.3f * float(x) + 0.2f * float(y));
    }
  return v;
}

// A stand-in for the shaded image: V in every channel.
ImageF grey_rgb(const ImageF& v) {
  ImageF out(v.width, v.height, 3);
  for (size_t p = 0; p < v.pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) out.data[p * 3 + size_t(c)] = v.data[p];
  return out;
}

// `v` with `value` added on the pixels of kind `k`.
ImageF plus_on(ImageF v, char k, bool cut, float value) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (kind(x, cut) == k) v.at(x, y, 0) += value;
  return v;
}

record::MetricsRecord measured(const ImageF& v, const ImageF& ref, const Regions& regions,
                               ImageF* flip_map = nullptr) {
  return measure(v, grey_rgb(v), ref, grey_rgb(ref), regions, kFlipDefaultPixelsPerDegree,
                 flip_map);
}

TEST(JobMetrics, GeometrysFlipSeesNothingTheTechniqueWritesOutsideIt) {
  const ImageF ref = reference_visibility(true);
  const Regions regions = regions_of(true, ref);
  // Right on the surface, wrong on the sky (V = 0.2 where it must be 1).
  const ImageF v = plus_on(ref, 's', true, -0.8f);
  const record::MetricsRecord m = measured(v, ref, regions);
  ASSERT_TRUE(m.visibility.geometry.has_value());
  const record::RegionStats& g = *m.visibility.geometry;
  EXPECT_EQ(g.rmse, 0.0);
  EXPECT_EQ(g.ssim, 1.0);
  // Within geometry the two images are the same: FLIP is 0, as SSIM is 1,
  // though FLIP's filters reach from the sky into the floor next to it.
  ASSERT_TRUE(g.flip_mean.has_value());
  EXPECT_EQ(*g.flip_mean, 0.0);
  // `all` holds the sky, and sees it.
  EXPECT_GT(*m.visibility.all.flip_mean, 0.01);
}

TEST(JobMetrics, TheTerminatorRegionIsTheHorizonCutPixelsMeasuredOnTheirOwn) {
  const ImageF ref = reference_visibility(true);
  const Regions regions = regions_of(true, ref);
  // Light leaking on the wall only: V 0.3 + 0.5 there.
  const ImageF leak = plus_on(ref, 'c', true, 0.5f);
  const record::MetricsRecord m = measured(leak, ref, regions);
  ASSERT_TRUE(m.visibility.terminator.has_value());
  const record::RegionStats& t = *m.visibility.terminator;
  EXPECT_EQ(t.pixel_count, 4 * kH);
  EXPECT_EQ(t.pixel_count, count_ones(regions.mask("terminator")));
  EXPECT_NEAR(t.rmse, 0.5, 1e-6);
  EXPECT_NEAR(t.mae, 0.5, 1e-6);
  EXPECT_NEAR(t.mean_signed, 0.5, 1e-6);
  EXPECT_NEAR(t.max_error, 0.5, 1e-6);
  EXPECT_EQ(t.frac_over_01, 1.0);
  EXPECT_LT(t.ssim, 0.99);
  ASSERT_TRUE(t.flip_mean.has_value());
  EXPECT_GT(*t.flip_mean, 0.05);
  ASSERT_TRUE(m.shaded.terminator.has_value());
  EXPECT_NEAR(m.shaded.terminator->rmse, 0.5, 1e-6);
  // No other region holds those pixels, nor sees them through SSIM's or
  // FLIP's windows.
  for (const record::RegionStats* s :
       {&m.visibility.all, &*m.visibility.geometry, &m.visibility.penumbra, &m.shaded.all,
        &*m.shaded.geometry}) {
    EXPECT_EQ(s->rmse, 0.0);
    EXPECT_EQ(s->ssim, 1.0);
    EXPECT_EQ(*s->flip_mean, 0.0);
  }
  // `all` is the sky, the geometry and the attached shadow.
  EXPECT_EQ(m.visibility.all.pixel_count + t.pixel_count, kW * kH);
  EXPECT_EQ(m.visibility.geometry->pixel_count, (40 - 8 - 4) * kH);

  // Measured on its own: what the technique does elsewhere changes none of
  // its figures (the reference's values stand outside it).
  const record::MetricsRecord worse = measured(plus_on(leak, 'g', true, -0.25f), ref, regions);
  EXPECT_GT(worse.visibility.geometry->rmse, 0.2);
  EXPECT_EQ(worse.visibility.terminator->to_json(), t.to_json());
  EXPECT_EQ(worse.shaded.terminator->to_json(), m.shaded.terminator->to_json());
}

// Each region's FLIP is the mean over its pixels of FLIP's whole map of its
// own image (the technique's values in the region, or in the measured
// pixels for the regions that share them, the reference's elsewhere), to
// the bit, however much of that map the job took from another image's.
TEST(JobMetrics, EachRegionsFlipIsTheMeanOfItsOwnImagesWholeMap) {
  const ImageF ref = reference_visibility(true);
  const Regions regions = regions_of(true, ref);
  // Wrong everywhere, differently on each kind of pixel.
  ImageF v = plus_on(plus_on(plus_on(ref, 'c', true, 0.4f), 'g', true, -0.2f), 's', true, -0.5f);
  for (std::size_t p = 0; p < v.data.size(); ++p) v.data[p] += 0.01f * float(p % 7);
  const record::MetricsRecord m = measured(v, ref, regions);
  const auto mean_over = [](const ImageF& map, const std::vector<uint8_t>& mask) {
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t p = 0; p < mask.size(); ++p)
      if (mask[p]) sum += map.data[p], ++n;
    return sum / double(n);
  };
  int checked = 0;
  for (const RegionMask& r : regions.masks) {
    if (r.per_job || count_ones(r.mask) == 0) continue;
    const bool own = r.surround == Surround::Reference;
    const ImageF own_image = with_unmeasured_from(v, ref, own ? r.mask : regions.measured);
    const double expected = mean_over(flip(ref, own_image).error, r.mask);
    const record::Region* region = record::find_region(r.key);
    ASSERT_NE(region, nullptr);
    record::ImageMetrics copy = m.visibility;
    SCOPED_TRACE(r.key);
    ASSERT_TRUE(region->slot(copy).flip_mean.has_value());
    EXPECT_EQ(*region->slot(copy).flip_mean, expected);
    ++checked;
  }
  EXPECT_GE(checked, 3);  // all, geometry, terminator at least
}

TEST(JobMetrics, AViewWithoutHorizonCutPixelsHasAnEmptyTerminatorRegion) {
  const ImageF ref = reference_visibility(false);
  const Regions regions = regions_of(false, ref);
  const record::MetricsRecord m = measured(plus_on(ref, 'g', false, -0.25f), ref, regions);
  ASSERT_TRUE(m.visibility.terminator.has_value());
  EXPECT_EQ(m.visibility.terminator->pixel_count, 0);
  EXPECT_TRUE(std::isnan(m.visibility.terminator->rmse));
  EXPECT_TRUE(std::isnan(m.visibility.terminator->ssim));
  EXPECT_FALSE(m.visibility.terminator->flip_mean.has_value());
}

TEST(JobMetrics, TheWholeImageFlipSeesEveryPixelAndItsMapIsTheOneReturned) {
  const ImageF ref = reference_visibility(true);
  const Regions regions = regions_of(true, ref);
  ImageF map;
  // Wrong on the wall only: every region but `terminator` sees no error,
  // the whole image does.
  const record::MetricsRecord m = measured(plus_on(ref, 'c', true, 0.5f), ref, regions, &map);
  EXPECT_EQ(*m.shaded.all.flip_mean, 0.0);
  ASSERT_TRUE(m.flip_shaded.has_value());
  EXPECT_GT(*m.flip_shaded, 0.0);
  ASSERT_EQ(map.pixel_count(), size_t(kW * kH));
  double sum = 0;
  for (float e : map.data) sum += e;
  EXPECT_NEAR(*m.flip_shaded, sum / double(kW * kH), 1e-9);
  EXPECT_GT(map.at(23, 20, 0), 0.1f);  // on the wall
  // The same images: 0.
  EXPECT_EQ(*measured(ref, ref, regions).flip_shaded, 0.0);
}

}  // namespace
}  // namespace sb::metrics
