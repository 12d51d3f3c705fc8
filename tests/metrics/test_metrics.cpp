// Known-answer tests for sb::metrics on constructed images.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "metrics/metrics.h"
#include "test_util.h"

namespace sb::metrics {

using core::ImageF;

namespace {

// Values on a 1/1024 grid in [0, 0.5], so adding 0.125 is exact in float.
ImageF grid_image(int w, int h, int c) {
  ImageF img(w, h, c);
  for (size_t i = 0; i < img.data.size(); ++i) {
    img.data[i] = static_cast<float>((i * 37) % 513) / 1024.0f;
  }
  return img;
}

TEST(metrics_compare, ConstantOffset) {
  const ImageF ref = grid_image(31, 17, 3);
  ImageF test = ref;
  for (float& v : test.data) v += 0.125f;
  const ErrorStats s = compare(test, ref);
  EXPECT_EQ(s.pixel_count, 31u * 17u);
  EXPECT_DOUBLE_EQ(s.rmse, 0.125);
  EXPECT_DOUBLE_EQ(s.mae, 0.125);
  EXPECT_DOUBLE_EQ(s.max_error, 0.125);
  // Every value ties; the first one (row-major, then channel) wins, as in OIIO.
  EXPECT_EQ(s.max_x, 0);
  EXPECT_EQ(s.max_y, 0);
  EXPECT_EQ(s.max_channel, 0);
  EXPECT_NEAR(s.psnr, 20.0 * std::log10(8.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.frac_over_001, 1.0);
  EXPECT_DOUBLE_EQ(s.frac_over_005, 1.0);
  EXPECT_DOUBLE_EQ(s.frac_over_01, 1.0);
  EXPECT_EQ(s.nonfinite_count, 0u);
}

TEST(metrics_compare, SignedErrorKeepsTheSign) {
  // Half the pixels 0.2 darker, the other half 0.1 lighter: mean -0.05, and
  // each half alone has its own sign.
  ImageF ref(4, 2, 1, 0.5f), test = ref;
  std::vector<uint8_t> dark(8, 0), light(8, 0);
  for (size_t i = 0; i < 8; ++i) {
    const bool d = i < 4;
    test.data[i] += d ? -0.2f : 0.1f;
    (d ? dark : light)[i] = 1;
  }
  EXPECT_NEAR(compare(test, ref).mean_signed, -0.05, 1e-6);
  EXPECT_NEAR(compare(test, ref, &dark).mean_signed, -0.2, 1e-6);
  EXPECT_NEAR(compare(test, ref, &light).mean_signed, 0.1, 1e-6);
  EXPECT_NEAR(compare(test, ref, &light).mae, 0.1, 1e-6);
}

TEST(metrics_penumbra, SoftUnionAddsTheTechniquesSoftPixels) {
  // ref: umbra, penumbra, lit, lit; technique: bleeding umbra, penumbra,
  // blurred lit, lit.
  ImageF ref(4, 1, 1), tech(4, 1, 1);
  ref.data = {0.0f, 0.5f, 1.0f, 1.0f};
  tech.data = {0.2f, 0.5f, 0.9f, 1.0f};
  EXPECT_EQ(penumbra_mask(ref), (std::vector<uint8_t>{0, 1, 0, 0}));
  EXPECT_EQ(soft_union_mask(tech, ref), (std::vector<uint8_t>{1, 1, 1, 0}));
  const std::vector<uint8_t> u = soft_union_mask(tech, ref);
  // Bleeding (+0.2) and blur (-0.1) keep their signs apart in the region.
  EXPECT_NEAR(compare(tech, ref, &u).mean_signed, (0.2 + 0.0 - 0.1) / 3.0, 1e-6);
}

TEST(metrics_compare, SingleDifferingPixel) {
  const int w = 20, h = 15;
  const ImageF ref(w, h, 3, 0.5f);
  ImageF test = ref;
  test.at(7, 4, 2) = 0.5625f;  // error exactly 1/16
  const ErrorStats s = compare(test, ref);
  const double n = w * h;
  EXPECT_EQ(s.pixel_count, static_cast<std::int64_t>(n));
  EXPECT_DOUBLE_EQ(s.max_error, 0.0625);
  EXPECT_EQ(s.max_x, 7);
  EXPECT_EQ(s.max_y, 4);
  EXPECT_EQ(s.max_channel, 2);
  EXPECT_DOUBLE_EQ(s.mae, 0.0625 / (3 * n));
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(0.0625 * 0.0625 / (3 * n)));
  EXPECT_NEAR(s.psnr, -20.0 * std::log10(s.rmse), 1e-12);
  // Fractions count pixels (not values); 1/16 is over 0.01 and 0.05, not 0.1.
  EXPECT_DOUBLE_EQ(s.frac_over_001, 1.0 / n);
  EXPECT_DOUBLE_EQ(s.frac_over_005, 1.0 / n);
  EXPECT_DOUBLE_EQ(s.frac_over_01, 0.0);
}

TEST(metrics_compare, FractionThresholdsAreStrict) {
  ImageF ref(4, 1, 1, 0.0f);
  ImageF test = ref;
  test.data = {0.0f, 0.01f, 0.05f, 0.2f};
  const ErrorStats s = compare(test, ref);
  // float(0.01) > 0.01 and float(0.05) > 0.05 as doubles, so compare against
  // what a strict '>' on the double error gives.
  EXPECT_DOUBLE_EQ(s.frac_over_001, (static_cast<double>(0.01f) > 0.01 ? 3 : 2) / 4.0);
  EXPECT_DOUBLE_EQ(s.frac_over_005, (static_cast<double>(0.05f) > 0.05 ? 2 : 1) / 4.0);
  EXPECT_DOUBLE_EQ(s.frac_over_01, 1 / 4.0);
  EXPECT_EQ(s.max_x, 3);
}

TEST(metrics_compare, IdenticalImages) {
  const ImageF a = test::noise_image(40, 30, 3, 7);
  const ErrorStats s = compare(a, a);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.mae, 0.0);
  EXPECT_EQ(s.max_error, 0.0);
  EXPECT_EQ(s.max_x, -1);
  EXPECT_EQ(s.max_y, -1);
  EXPECT_EQ(s.max_channel, -1);
  EXPECT_TRUE(std::isinf(s.psnr) && s.psnr > 0);
  EXPECT_DOUBLE_EQ(s.ssim, 1.0);
  EXPECT_EQ(s.frac_over_001, 0.0);
}

TEST(metrics_compare, MaskRestrictsEveryFigure) {
  const int w = 40, h = 30;
  const ImageF ref = test::noise_image(w, h, 1, 11);
  ImageF test = ref;
  // Large errors on the left half, small ones on the right half.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) test.at(x, y) += x < w / 2 ? 0.5f : 0.02f;
  }
  std::vector<uint8_t> right(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = w / 2; x < w; ++x) right[static_cast<size_t>(y) * w + x] = 255;
  }
  const ErrorStats all = compare(test, ref);
  const ErrorStats s = compare(test, ref, &right);
  EXPECT_EQ(s.pixel_count, static_cast<std::int64_t>(w / 2 * h));
  EXPECT_NEAR(all.max_error, 0.5, 1e-6);
  EXPECT_NEAR(s.max_error, 0.02, 1e-6);
  EXPECT_GE(s.max_x, w / 2);
  EXPECT_NEAR(s.mae, 0.02, 1e-6);
  EXPECT_NEAR(s.rmse, 0.02, 1e-6);
  EXPECT_DOUBLE_EQ(s.frac_over_001, 1.0);
  EXPECT_DOUBLE_EQ(s.frac_over_005, 0.0);
  EXPECT_DOUBLE_EQ(all.frac_over_005, 0.5);

  // Masked SSIM = mean of the SSIM map over masked pixels of the interior
  // (at least 5 pixels from every border).
  const ImageF map = ssim_map(test, ref);
  double sum = 0;
  size_t count = 0;
  for (int y = kSsimRadius; y < h - kSsimRadius; ++y) {
    for (int x = kSsimRadius; x < w - kSsimRadius; ++x) {
      if (!right[static_cast<size_t>(y) * w + x]) continue;
      sum += map.at(x, y);
      ++count;
    }
  }
  EXPECT_NEAR(s.ssim, sum / static_cast<double>(count), 1e-6);
  EXPECT_GT(s.ssim, all.ssim);
}

TEST(metrics_compare, EmptyMaskGivesNaN) {
  const ImageF a = test::noise_image(16, 16, 1, 1), b = test::noise_image(16, 16, 1, 2);
  const std::vector<uint8_t> none(a.pixel_count(), 0);
  const ErrorStats s = compare(a, b, &none);
  EXPECT_EQ(s.pixel_count, 0u);
  EXPECT_TRUE(std::isnan(s.rmse));
  EXPECT_TRUE(std::isnan(s.ssim));
  EXPECT_TRUE(std::isnan(ssim(a, b, 1.0, &none)));
  // A mask that only covers the cropped border leaves SSIM undefined too.
  std::vector<uint8_t> border(a.pixel_count(), 0);
  border[0] = 1;
  EXPECT_EQ(compare(a, b, &border).pixel_count, 1u);
  EXPECT_TRUE(std::isnan(compare(a, b, &border).ssim));
}

TEST(metrics_compare, RejectsBadArguments) {
  const ImageF a(16, 16, 1), b(16, 16, 3), c(15, 16, 1);
  EXPECT_THROW(compare(a, b), std::invalid_argument);
  EXPECT_THROW(compare(a, c), std::invalid_argument);
  const std::vector<uint8_t> short_mask(10, 1);
  EXPECT_THROW(compare(a, a, &short_mask), std::invalid_argument);
  EXPECT_THROW(ssim(a, a, 1.0, &short_mask), std::invalid_argument);
  EXPECT_THROW(ssim(a, a, 0.0), std::invalid_argument);
  const ImageF tiny(10, 40, 1);
  EXPECT_THROW(ssim(tiny, tiny), std::invalid_argument);
  // compare() still reports the other figures for images too small for SSIM.
  const ErrorStats s = compare(tiny, tiny);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_TRUE(std::isnan(s.ssim));
}

TEST(metrics_compare, NonFiniteValues) {
  const ImageF ref = grid_image(8, 8, 1);
  ImageF test = ref;
  test.at(2, 3) = std::numeric_limits<float>::quiet_NaN();
  test.at(5, 6) += 0.25f;
  ImageF both_nan = ref;
  both_nan.at(1, 1) = std::numeric_limits<float>::quiet_NaN();
  const ErrorStats s = compare(test, ref);
  EXPECT_EQ(s.nonfinite_count, 1u);
  EXPECT_TRUE(std::isinf(s.max_error));
  EXPECT_EQ(s.max_x, 2);
  EXPECT_EQ(s.max_y, 3);
  // The NaN stays out of the sums, the divisor stays 64.
  EXPECT_DOUBLE_EQ(s.mae, 0.25 / 64);
  EXPECT_DOUBLE_EQ(s.frac_over_01, 2.0 / 64);
  // NaN against NaN is a match.
  const ErrorStats m = compare(both_nan, both_nan);
  EXPECT_EQ(m.nonfinite_count, 0u);
  EXPECT_EQ(m.max_error, 0.0);
}

TEST(metrics_ssim, ConstantImagesClosedForm) {
  // No variance: SSIM = (2ab + C1) / (a^2 + b^2 + C1) at every pixel.
  const ImageF a(23, 19, 1, 0.5f), b(23, 19, 1, 0.25f);
  const double c1 = 0.01 * 0.01;
  EXPECT_NEAR(ssim(a, b), (2 * 0.5 * 0.25 + c1) / (0.25 + 0.0625 + c1), 1e-12);
  // data_range scales C1.
  const double c1r = (0.01 * 4) * (0.01 * 4);
  EXPECT_NEAR(ssim(a, b, 4.0), (2 * 0.5 * 0.25 + c1r) / (0.25 + 0.0625 + c1r), 1e-12);
}

TEST(metrics_ssim, ChannelsAreAveraged) {
  const ImageF a = test::noise_image(30, 20, 3, 5), b = test::noise_image(30, 20, 3, 6);
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    ImageF ac(30, 20, 1), bc(30, 20, 1);
    for (size_t p = 0; p < ac.data.size(); ++p) {
      ac.data[p] = a.data[p * 3 + c];
      bc.data[p] = b.data[p * 3 + c];
    }
    sum += ssim(ac, bc);
  }
  EXPECT_NEAR(ssim(a, b), sum / 3, 1e-12);
}

TEST(metrics_ssim, LargeImageIsDeterministic) {
  // Exercises the TBB split; the row-ordered reduction makes it bit-exact.
  const ImageF a = test::noise_image(301, 207, 1, 9);
  const ImageF b = test::blur_shift(a, 1, 0);
  const double first = ssim(a, b);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(ssim(a, b), first);
  EXPECT_GT(first, -1.0);
  EXPECT_LT(first, 1.0);
}

TEST(metrics_penumbra, OpenIntervalWithEps) {
  ImageF v(6, 1, 1);
  v.data = {0.0f, 1.0f, 0.5f, 1e-7f, 1.0f - 1e-7f, 2e-6f};
  const std::vector<uint8_t> m = penumbra_mask(v);
  const std::vector<uint8_t> want = {0, 0, 1, 0, 0, 1};
  EXPECT_EQ(m, want);
  // A wider eps shrinks the penumbra.
  EXPECT_EQ(penumbra_mask(v, 0.6f), std::vector<uint8_t>(6, 0));
  // Multi-channel: any channel strictly inside counts.
  ImageF rgb(2, 1, 3, 1.0f);
  rgb.at(1, 0, 2) = 0.3f;
  EXPECT_EQ(penumbra_mask(rgb), (std::vector<uint8_t>{0, 1}));
}

TEST(metrics_heatmap, Endpoints) {
  const ImageF ref(5, 1, 2, 0.25f);
  ImageF test = ref;
  test.at(1, 0, 1) += 0.5f;  // exactly full scale
  test.at(2, 0, 0) += 3.0f;  // beyond full scale
  test.at(3, 0, 0) += 0.125f;
  test.at(4, 0, 1) = std::numeric_limits<float>::quiet_NaN();
  const ImageF h = error_heatmap(test, ref, 0.5f);
  ASSERT_EQ(h.channels, 3);
  ASSERT_EQ(h.width, 5);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(h.at(0, 0, c), 0.0f);  // no error: black
  float top[3];
  heatmap_colour(1.0f, top);
  EXPECT_NEAR(top[0], 252 / 255.0f, 1e-6);
  EXPECT_NEAR(top[1], 1.0f, 1e-6);
  EXPECT_NEAR(top[2], 164 / 255.0f, 1e-6);
  for (int x : {1, 2, 4}) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(h.at(x, 0, c), top[c]) << "x=" << x;
  }
  // In between: neither end, and brightness grows along the ramp.
  float prev = -1;
  for (int i = 0; i <= 20; ++i) {
    float rgb[3];
    heatmap_colour(static_cast<float>(i) / 20, rgb);
    const float luma = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
    EXPECT_GT(luma, prev) << i;
    prev = luma;
  }
  EXPECT_GT(h.at(3, 0, 0), 0.0f);
  EXPECT_LT(h.at(3, 0, 1), top[1]);
  EXPECT_THROW(error_heatmap(test, ref, 0.0f), std::invalid_argument);
}

}  // namespace
}  // namespace sb::metrics

// The several-masks compare() is one pass over the pixels and one of the
// SSIM window: each mask's figures must be the one-mask call's, bit for bit
// (including where the largest error lies, ties to the first pixel, a mask
// that holds nothing, a NaN, and no mask at all).
TEST(metrics_compare, SeveralMasksEqualOneCallPerMask) {
  for (int channels : {1, 3}) {
    SCOPED_TRACE(channels);
    sb::core::ImageF ref(37, 29, channels), test(37, 29, channels);
    for (size_t i = 0; i < ref.data.size(); ++i) {
      ref.data[i] = float((i * 7919) % 101) / 100.0f;
      test.data[i] = ref.data[i] + (i % 5 == 0 ? float((i * 31) % 17) / 200.0f : 0.0f);
    }
    test.data[40] = std::numeric_limits<float>::quiet_NaN();
    std::vector<uint8_t> left(ref.pixel_count()), sparse(ref.pixel_count()),
        none(ref.pixel_count());
    for (size_t p = 0; p < left.size(); ++p) {
      left[p] = (p % 37) < 18 ? 1 : 0;
      sparse[p] = p % 3 == 0 ? 1 : 0;
    }
    const std::vector<const std::vector<uint8_t>*> masks = {&left, nullptr, &sparse, &none};
    const std::vector<sb::metrics::ErrorStats> together = sb::metrics::compare(test, ref, masks);
    ASSERT_EQ(together.size(), masks.size());
    for (size_t m = 0; m < masks.size(); ++m) {
      SCOPED_TRACE(m);
      const sb::metrics::ErrorStats alone = sb::metrics::compare(test, ref, masks[m]);
      const sb::metrics::ErrorStats& t = together[m];
      EXPECT_EQ(t.pixel_count, alone.pixel_count);
      EXPECT_EQ(t.nonfinite_count, alone.nonfinite_count);
      for (const auto& [a, b] : {std::pair{t.rmse, alone.rmse},
                                 {t.mae, alone.mae},
                                 {t.max_error, alone.max_error},
                                 {t.mean_signed, alone.mean_signed},
                                 {t.psnr, alone.psnr},
                                 {t.ssim, alone.ssim},
                                 {t.frac_over_001, alone.frac_over_001},
                                 {t.frac_over_01, alone.frac_over_01}})
        EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << a << " vs " << b;
      EXPECT_EQ(t.max_x, alone.max_x);
      EXPECT_EQ(t.max_y, alone.max_y);
      EXPECT_EQ(t.max_channel, alone.max_channel);
    }
    EXPECT_EQ(together[3].pixel_count, 0u);
    EXPECT_TRUE(std::isnan(together[3].ssim));
  }
}
