// FLIP computed only where it is needed (metrics/flip.h flip_map_within,
// FlipReference, metrics/flip_reuse.h): at every pixel asked for, the bits
// of the whole map flip() makes, on every vector width this CPU runs, with
// the reference's half made once or not; the mask growth it relies on
// against a brute-force search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "core/image.h"
#include "metrics/flip.h"
#include "metrics/flip_reuse.h"
#include "metrics/regions.h"

namespace sb::metrics {

using core::ImageF;

namespace {

ImageF random_image(int w, int h, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  ImageF out(w, h, channels);
  for (float& v : out.data) v = u(rng);
  return out;
}

// Masks of the shapes a job's regions take: scattered pixels, a thin
// crescent (a terminator), one corner pixel, every pixel, none.
std::vector<std::vector<uint8_t>> masks(int w, int h) {
  std::vector<std::vector<uint8_t>> out;
  std::mt19937 rng(7);
  std::vector<uint8_t> scattered(static_cast<std::size_t>(w * h));
  for (auto& m : scattered) m = rng() % 50 == 0 ? 1 : 0;
  out.push_back(scattered);
  std::vector<uint8_t> crescent(static_cast<std::size_t>(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = x - 0.5 * w, dy = y - 0.5 * h, r = 0.3 * std::min(w, h);
      const double d = std::sqrt(dx * dx + dy * dy);
      crescent[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
               static_cast<std::size_t>(x)] = d > r && d < r + 2 && dy > 0 ? 1 : 0;
    }
  out.push_back(crescent);
  std::vector<uint8_t> corner(static_cast<std::size_t>(w * h));
  corner.back() = 1;
  out.push_back(corner);
  out.emplace_back(static_cast<std::size_t>(w * h), 1);
  out.emplace_back(static_cast<std::size_t>(w * h), 0);
  return out;
}

// At each pixel of `mask`, `map`'s value is `whole`'s, to the bit; 0
// elsewhere.
void expect_map_within(const ImageF& map, const ImageF& whole, const std::vector<uint8_t>& mask) {
  ASSERT_EQ(map.data.size(), whole.data.size());
  std::size_t wrong = 0, nonzero_outside = 0;
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (mask[p] && map.data[p] != whole.data[p]) ++wrong;
    if (!mask[p] && map.data[p] != 0.0f) ++nonzero_outside;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(nonzero_outside, 0u);
}

}  // namespace

TEST(FlipMapWithin, GivesFlipsBitsAtEveryNeededPixelOnEveryVectorWidth) {
  using detail::SimdPath;
  // Sizes that are not multiples of a block (256 x 128), a vector or a tile,
  // one narrower than a filter, grey and colour.
  const struct { int w, h, channels; } sizes[] = {{300, 137, 3}, {131, 65, 1}, {5, 70, 3}};
  for (const auto& size : sizes) {
    const ImageF ref = random_image(size.w, size.h, size.channels, 1);
    const ImageF test = random_image(size.w, size.h, size.channels, 2);
    for (const SimdPath path : {SimdPath::Baseline, SimdPath::Avx2, SimdPath::Avx512}) {
      if (!detail::runs_here(path)) continue;
      const ImageF whole = detail::flip_on(path, ref, test).error;
      const auto all = masks(size.w, size.h);
      for (std::size_t m = 0; m < all.size(); ++m) {
        SCOPED_TRACE(detail::to_string(path) + ", " + std::to_string(size.w) + "x" +
                     std::to_string(size.h) + ", mask " + std::to_string(m));
        expect_map_within(detail::flip_map_within_on(path, ref, test, all[m]), whole, all[m]);
      }
    }
  }
}

// The reference's half prepared on one vector width and the test's on
// another: still flip()'s map and mean, to the bit.
TEST(FlipReference, GivesFlipsBitsOnEveryPairOfVectorWidths) {
  using detail::SimdPath;
  const struct { int w, h, channels; } sizes[] = {{300, 137, 3}, {131, 65, 1}, {5, 70, 4}};
  const SimdPath paths[] = {SimdPath::Baseline, SimdPath::Avx2, SimdPath::Avx512};
  for (const auto& size : sizes) {
    const ImageF ref = random_image(size.w, size.h, size.channels, 5);
    const ImageF test = random_image(size.w, size.h, size.channels, 6);
    const FlipResult whole = flip(ref, test);
    const auto all = masks(size.w, size.h);
    for (const SimdPath prepared_on : paths) {
      if (!detail::runs_here(prepared_on)) continue;
      const FlipReference prepared(ref, kFlipDefaultPixelsPerDegree, prepared_on);
      for (const SimdPath path : paths) {
        if (!detail::runs_here(path)) continue;
        SCOPED_TRACE(detail::to_string(prepared_on) + " then " + detail::to_string(path) + ", " +
                     std::to_string(size.w) + "x" + std::to_string(size.h));
        const FlipResult got = detail::flip_on(path, prepared, test);
        EXPECT_EQ(got.error.data, whole.error.data);
        EXPECT_EQ(got.mean, whole.mean);
        expect_map_within(detail::flip_map_within_on(path, prepared, test, all[1]), whole.error,
                          all[1]);
      }
    }
  }
}

TEST(FlipReference, RefusesATestImageOfAnotherSize) {
  const FlipReference prepared(random_image(16, 16, 3, 1));
  EXPECT_THROW(flip(prepared, ImageF(16, 15, 3)), std::invalid_argument);
  EXPECT_THROW(flip_map_within(prepared, ImageF(15, 16, 3), std::vector<uint8_t>(240, 1)),
               std::invalid_argument);
  EXPECT_THROW(FlipReference(ImageF(16, 16, 2)), std::invalid_argument);
}

TEST(FlipMapWithin, RefusesAMaskOfAnotherSize) {
  const ImageF a(8, 8, 3);
  EXPECT_THROW(flip_map_within(a, a, std::vector<uint8_t>(63, 1)), std::invalid_argument);
}

// A region's own image (the technique's values inside it, the reference's
// outside) next to a known one that differs from it in a patch: the map
// reuses the known values away from the patch and is still flip()'s.
TEST(FlipMapReusing, EqualsFlipsMapWhereverTheKnownImageDiffers) {
  const int w = 257, h = 131;
  const ImageF ref = random_image(w, h, 3, 3);
  const ImageF known_test = random_image(w, h, 3, 4);
  const ImageF known_map = flip(ref, known_test).error;
  ImageF test = known_test;
  for (int y = 40; y < 60; ++y)
    for (int x = 100; x < 103; ++x)
      for (int c = 0; c < 3; ++c) test.at(x, y, c) = ref.at(x, y, c);
  const ImageF whole = flip(ref, test).error;
  const std::vector<KnownFlipMap> known = {{&known_test, &known_map}};
  const FlipReference prepared(ref);
  // The known map is wrong near the patch: reusing it there would show.
  std::size_t differ = 0;
  for (std::size_t p = 0; p < whole.data.size(); ++p) differ += whole.data[p] != known_map.data[p];
  ASSERT_GT(differ, 60u);
  for (const auto& mask : masks(w, h))
    expect_map_within(flip_map_reusing(prepared, test, &mask, known), whole, mask);
  // Every pixel, no mask: the whole map.
  EXPECT_EQ(flip_map_reusing(prepared, test, nullptr, known).data, whole.data);
  // A known image of another size or channel count is not used.
  const ImageF grey(w, h, 1), grey_map(w, h, 1);
  EXPECT_EQ(flip_map_reusing(prepared, test, nullptr, {{&grey, &grey_map}}).data, whole.data);
}

TEST(Dilated, MarksEveryPixelWithinTheSquareOfAOne) {
  std::mt19937 rng(11);
  for (const auto& [w, h, radius] : {std::array{17, 9, 0}, {17, 9, 2}, {5, 31, 3}, {4, 4, 10}}) {
    std::vector<uint8_t> mask(static_cast<std::size_t>(w * h));
    for (auto& m : mask) m = rng() % 13 == 0 ? 1 : 0;
    const std::vector<uint8_t> grown = dilated(mask, w, h, radius);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        bool near = false;
        for (int v = std::max(0, y - radius); v <= std::min(h - 1, y + radius); ++v)
          for (int u = std::max(0, x - radius); u <= std::min(w - 1, x + radius); ++u)
            near = near || mask[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) +
                                static_cast<std::size_t>(u)] != 0;
        EXPECT_EQ(grown[static_cast<std::size_t>(y * w + x)], near ? 1 : 0)
            << x << "," << y << " radius " << radius;
      }
  }
}

// flip_radius is the reach of a change: a pixel changed at distance
// radius + 1 leaves a pixel's value as it was, one at the radius along x or y
// does not
// (for these images).
TEST(FlipRadius, IsHowFarAChangeReaches) {
  const int r = flip_radius(kFlipDefaultPixelsPerDegree);
  ASSERT_GT(r, 0);
  const int w = 4 * r + 9, h = 4 * r + 9, cx = w / 2, cy = h / 2;
  const ImageF ref = random_image(w, h, 3, 5), test = random_image(w, h, 3, 6);
  const float before = flip(ref, test).error.at(cx, cy, 0);
  for (const auto& [dx, dy, changes] :
       {std::array{r + 1, 0, 0}, {0, r + 1, 0}, {r + 1, r + 1, 0}, {r, 0, 1}, {0, -r, 1}}) {
    ImageF moved = test;
    for (int c = 0; c < 3; ++c)
      moved.at(cx + dx, cy + dy, c) = 1.0f - moved.at(cx + dx, cy + dy, c);
    const float after = flip(ref, moved).error.at(cx, cy, 0);
    if (changes)
      EXPECT_NE(after, before) << dx << "," << dy;
    else
      EXPECT_EQ(after, before) << dx << "," << dy;
  }
}

}  // namespace sb::metrics
