// FLIP (metrics/flip.h) against NVIDIA's reference implementation: its
// error maps and means on two image pairs at two viewing distances, made
// once by that implementation and kept in tests/metrics/flip_data (README
// there says how); and against what the paper's formulas give by hand on
// images simple enough to work out.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/image.h"
#include "metrics/flip.h"
#include "metrics/image_io.h"

namespace sb::metrics {

using core::ImageF;

namespace {

const std::filesystem::path kData =
    std::filesystem::path(SHADOWBENCH_SOURCE_DIR) / "tests" / "metrics" / "flip_data";

struct OracleCase {
  const char* pair;
  const char* reference;
  const char* test;
  double ppd;
  const char* map;
  double mean;  // printed by the reference implementation (flip_data/README.md)
};

constexpr OracleCase kCases[] = {
    {"render", "render_reference.png", "render_pcss.png", 67.020645, "render_67ppd.exr",
     0.030221895},
    {"render", "render_reference.png", "render_pcss.png", 30.0, "render_30ppd.exr", 0.035399785},
    {"natural", "natural_reference.png", "natural_test.png", 67.020645, "natural_67ppd.exr",
     0.192814502},
    {"natural", "natural_reference.png", "natural_test.png", 30.0, "natural_30ppd.exr",
     0.228492210},
};

ImageF decoded(const char* name) {
  return linear_from_srgb(io::read_image((kData / name).string()));
}

TEST(Flip, AgreesWithTheReferenceImplementationOnItsMapsAndMeans) {
  for (const OracleCase& c : kCases) {
    SCOPED_TRACE(std::string(c.pair) + " at " + std::to_string(c.ppd) + " ppd");
    const FlipResult r = flip(decoded(c.reference), decoded(c.test), c.ppd);
    const ImageF expected = io::read_image((kData / c.map).string());
    ASSERT_EQ(r.error.width, expected.width);
    ASSERT_EQ(r.error.height, expected.height);
    ASSERT_EQ(expected.channels, 1);
    // Where the two images agree, the colour difference is a sum of
    // rounding residues, and its 0.7th power has an unbounded slope at 0:
    // there the two implementations' float roundings show (its
    // misc/precision.md says as much of its own implementations). Elsewhere
    // they agree to 1e-4.
    double worst = 0;
    std::size_t near_zero_disagreements = 0;
    for (std::size_t i = 0; i < expected.data.size(); ++i) {
      const double ours = r.error.data[i], theirs = expected.data[i];
      const double d = std::abs(ours - theirs);
      worst = std::max(worst, d);
      if (d <= 1e-4) continue;
      EXPECT_LT(std::max(ours, theirs), 1e-3)
          << "pixel " << i % expected.width << "," << i / expected.width;
      ++near_zero_disagreements;
    }
    EXPECT_LT(worst, 2e-4);
    EXPECT_LT(near_zero_disagreements, expected.data.size() / 1000);
    EXPECT_NEAR(r.mean, c.mean, 1e-6);  // the issue asks for 1e-4
  }
}

TEST(Flip, TheDefaultViewingDistanceIsThePapersMonitor) {
  // 0.7 m from a 0.7 m wide, 3840 pixel monitor, by the paper's
  // ppd = distance * (pixels / width) * pi / 180.
  EXPECT_NEAR(kFlipDefaultPixelsPerDegree, 0.7 * (3840.0 / 0.7) * M_PI / 180.0, 1e-12);
}

TEST(Flip, IdenticalImagesHaveNoError) {
  const ImageF a = decoded("natural_reference.png");
  const FlipResult r = flip(a, a);
  EXPECT_EQ(r.mean, 0.0);
  for (float v : r.error.data) ASSERT_EQ(v, 0.0f);
}

// Flat images have no edges or points (feature difference 0), and the
// low-pass filters keep a flat colour: FLIP is the remapped colour
// difference alone, the paper's formula on the two colours.
TEST(Flip, TwoFlatGreysGiveThePapersColourDifferenceEverywhere) {
  const double g1 = 0.2, g2 = 0.6;
  ImageF a(40, 30, 3, float(g1)), b(40, 30, 3, float(g2));
  const FlipResult r = flip(a, b);
  // Hunt-adjusted CIELAB of a linear sRGB colour, in double: the sRGB
  // matrix in the exact fractions the reference implementation uses (whose
  // row sums are its white), its D65 white, CIELAB's f.
  auto lab = [](double r_, double g_, double b_) {
    const double x = (10135552.0 * r_ + 8788810.0 * g_ + 4435075.0 * b_) / 24577794.0 / 0.950428545;
    const double y = (2613072.0 * r_ + 8788810.0 * g_ + 887015.0 * b_) / 12288897.0;
    const double z = (1425312.0 * r_ + 8788810.0 * g_ + 70074185.0 * b_) / 73733382.0 / 1.088900371;
    auto f = [](double t) {
      return t > std::pow(6.0 / 29.0, 3) ? std::cbrt(t)
                                         : t / (3 * std::pow(6.0 / 29.0, 2)) + 4.0 / 29.0;
    };
    const double l = 116 * f(y) - 16;
    return std::array<double, 3>{l, 0.01 * l * 500 * (f(x) - f(y)), 0.01 * l * 200 * (f(y) - f(z))};
  };
  auto hyab = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
  };
  const double d = std::pow(hyab(lab(g1, g1, g1), lab(g2, g2, g2)), 0.7);
  // cmax: green (0, 1, 0) to blue (0, 0, 1).
  const double cmax = std::pow(hyab(lab(0, 1, 0), lab(0, 0, 1)), 0.7);
  const double expected = d < 0.4 * cmax ? d * 0.95 / (0.4 * cmax)
                                         : 0.95 + (d - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
  // Not closer: on a flat field the derivative filters leave float residues
  // (about 1e-8; their taps cancel only to rounding), and the feature
  // difference is their square root (q_f = 0.5), which moves the exponent
  // 1 - feature by about 1e-4. The reference implementation has the same.
  EXPECT_NEAR(r.mean, expected, 1e-4);
  for (float v : r.error.data) ASSERT_NEAR(v, expected, 1e-4);
}

TEST(Flip, IsSymmetricInItsTwoImages) {
  const ImageF a = decoded("render_reference.png"), b = decoded("render_pcss.png");
  const FlipResult ab = flip(a, b), ba = flip(b, a);
  EXPECT_EQ(ab.error.data, ba.error.data);
}

TEST(Flip, AGreyImageIsItsValueInEveryChannel) {
  const ImageF rgb = decoded("render_reference.png");
  ImageF grey(rgb.width, rgb.height, 1), grey3(rgb.width, rgb.height, 3);
  for (std::size_t p = 0; p < rgb.pixel_count(); ++p) {
    grey.data[p] = rgb.data[p * 3 + 1];
    for (int c = 0; c < 3; ++c) grey3.data[p * 3 + c] = rgb.data[p * 3 + 1];
  }
  const ImageF other = decoded("render_pcss.png");
  EXPECT_EQ(flip(grey, other).error.data, flip(grey3, other).error.data);
}

TEST(Flip, ANonFinitePixelIsBlackAndOutOfRangeValuesAreClamped) {
  const ImageF ref = decoded("render_reference.png");
  ImageF broken = decoded("render_pcss.png"), fixed = broken;
  const std::size_t nan_at = (40 * std::size_t(ref.width) + 50) * 3;
  const std::size_t big_at = (90 * std::size_t(ref.width) + 120) * 3 + 1;
  broken.data[nan_at] = std::nan("");
  fixed.data[nan_at] = 0.0f;
  broken.data[big_at] = 7.0f;
  fixed.data[big_at] = 1.0f;
  const FlipResult a = flip(ref, broken), b = flip(ref, fixed);
  EXPECT_EQ(a.error.data, b.error.data);
  EXPECT_TRUE(std::isfinite(a.mean));
}

// Every vector width this CPU runs (metrics/simd_path.h) gives the bits of
// the baseline, on the oracle's pairs at both distances, and on an image
// whose width is not a multiple of any vector or tile (the remainders' loops)
// and narrower than a filter (edge columns repeated past both sides).
TEST(Flip, EveryVectorWidthGivesTheBaselinesBits) {
  using detail::SimdPath;
  ImageF odd_ref(300, 37, 3), odd_test(300, 37, 3), narrow_ref(5, 70, 1), narrow_test(5, 70, 1);
  for (std::size_t i = 0; i < odd_ref.data.size(); ++i) {
    odd_ref.data[i] = static_cast<float>((i * 7919) % 997) / 996.0f;
    odd_test.data[i] = static_cast<float>((i * 104729) % 991) / 990.0f;
  }
  for (std::size_t i = 0; i < narrow_ref.data.size(); ++i) {
    narrow_ref.data[i] = static_cast<float>(i % 5) / 4.0f;
    narrow_test.data[i] = static_cast<float>(i % 7) / 6.0f;
  }
  const ImageF render_ref = decoded("render_reference.png"), render = decoded("render_pcss.png");
  const struct {
    const char* name;
    const ImageF &ref, &test;
    double ppd;
  } cases[] = {{"render 67", render_ref, render, 67.020645},
               {"render 30", render_ref, render, 30.0},
               {"300x37", odd_ref, odd_test, kFlipDefaultPixelsPerDegree},
               {"5x70 grey", narrow_ref, narrow_test, kFlipDefaultPixelsPerDegree}};
  int paths = 0;
  for (const SimdPath path : {SimdPath::Avx2, SimdPath::Avx512}) {
    if (!detail::runs_here(path)) continue;
    ++paths;
    for (const auto& c : cases) {
      SCOPED_TRACE(detail::to_string(path) + " on " + c.name);
      const FlipResult base = detail::flip_on(SimdPath::Baseline, c.ref, c.test, c.ppd);
      const FlipResult wide = detail::flip_on(path, c.ref, c.test, c.ppd);
      EXPECT_EQ(wide.error.data, base.error.data);
      EXPECT_EQ(wide.mean, base.mean);
    }
  }
  std::printf("compared %d wider path(s) with the baseline\n", paths);
  EXPECT_EQ(detail::flip_on(detail::widest_simd_path(), render_ref, render).error.data,
            flip(render_ref, render).error.data);
}

TEST(Flip, RefusesMismatchedOrEmptyImagesAndAnImpossibleDistance) {
  const ImageF a(8, 8, 3), b(8, 9, 3), two(8, 8, 2);
  EXPECT_THROW(flip(a, b), std::invalid_argument);
  EXPECT_THROW(flip(a, two), std::invalid_argument);
  EXPECT_THROW(flip(ImageF(), ImageF()), std::invalid_argument);
  EXPECT_THROW(flip(a, a, 0.0), std::invalid_argument);
  EXPECT_THROW(flip(a, a, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace sb::metrics
