// FLIP's map and mean: the arguments checked, the filters and the colour
// remapping set up, the tiles run in parallel (flip_tile.h), the map summed.
#include "metrics/flip.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/flip_colour.h"
#include "metrics/flip_filters.h"
#include "metrics/flip_tile.h"
#include "metrics/simd_path.h"

namespace sb::metrics {

using core::ImageF;
using flip_detail::feature_filters;
using flip_detail::inverse;
using flip_detail::kPc;
using flip_detail::kPreparedPlanes;
using flip_detail::kPt;
using flip_detail::kRgbToXyz;
using flip_detail::max_colour_distance;
using flip_detail::Scratch;
using flip_detail::Setup;
using flip_detail::Sides;
using flip_detail::spatial_filters;
using flip_detail::Tile;
using flip_detail::tile_on;

namespace {

// The arguments checked, and everything the tiles share. `reference` is
// null when the tiles filter the test image only.
Setup make_setup(detail::SimdPath path, const ImageF* reference, const ImageF& test,
                 double pixels_per_degree) {
  auto channels_ok = [](const ImageF& i) {
    return i.channels == 1 || i.channels == 3 || i.channels == 4;
  };
  if (reference != nullptr && (reference->width != test.width || reference->height != test.height))
    throw std::invalid_argument("flip: the images differ in size");
  if ((reference != nullptr && !channels_ok(*reference)) || !channels_ok(test))
    throw std::invalid_argument("flip: expected 1, 3 or 4 channels");
  if (test.pixel_count() == 0) throw std::invalid_argument("flip: empty image");
  if (!(pixels_per_degree > 0 && pixels_per_degree <= 1000))
    throw std::invalid_argument("flip: pixels per degree must be in (0, 1000], not " +
                                std::to_string(pixels_per_degree));
  if (!runs_here(path)) throw std::invalid_argument("flip: this CPU has no " + to_string(path));

  Setup s{{reference, &test},
          test.width,
          test.height,
          spatial_filters(pixels_per_degree),
          feature_filters(pixels_per_degree),
          0,
          inverse(kRgbToXyz),
          0,
          0,
          0,
          1.0f / std::sqrt(2.0f)};
  s.radius = std::max(s.spatial.radius, s.features.radius);
  const float cmax = max_colour_distance(), pccmax = kPc * cmax;
  // The remapping's two slopes: [0, p_c cmax) onto [0, p_t), the rest onto [p_t, 1].
  s.knee = pccmax;
  s.slope_below = kPt / pccmax;
  s.slope_above = (1.0f - kPt) / (cmax - pccmax);
  return s;
}

// The tiles read the reference's prepared planes instead of filtering it.
Setup make_setup(detail::SimdPath path, const FlipReference& reference, const ImageF& test) {
  if (reference.width() != test.width || reference.height() != test.height)
    throw std::invalid_argument("flip: the images differ in size");
  Setup s = make_setup(path, nullptr, test, reference.pixels_per_degree());
  s.sides = Sides::TestOnly;
  s.prepared_in = reference.planes().data();
  return s;
}

// Tiles of 256 columns by 128 rows: the rings fit a core's L2 cache, and
// the first 2 radius rows each tile filters before its first output row
// cost a sixth more of the horizontal filtering.
constexpr int kTileColumns = 256, kTileRows = 128;

std::vector<Tile> whole_image_tiles(int w, int h) {
  std::vector<Tile> tiles;
  for (int y0 = 0; y0 < h; y0 += kTileRows)
    for (int x0 = 0; x0 < w; x0 += kTileColumns)
      tiles.push_back({y0, std::min(h, y0 + kTileRows), x0, std::min(w, x0 + kTileColumns)});
  return tiles;
}

// The whole image's tiles, each cut to the rows and columns of its needed
// pixels: a thin region (a terminator's crescents) costs its own rows and
// columns, plus 2 radius rows and columns of filtering per tile. (Smaller
// blocks fit such a region closer, but their margins cost more: counted on a
// 640x480 sphere grid's terminator mask, the cut tiles with their margins
// cover 0.44 of the image in tiles of 256 x 128, 0.49 in 128 x 64, 0.58 in
// 32 x 32.)
std::vector<Tile> tiles_cut_to(const std::vector<uint8_t>& needed, int w, int h) {
  if (needed.size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h))
    throw std::invalid_argument("flip: the mask of needed pixels is not the image's size");
  std::vector<Tile> tiles;
  for (int by = 0; by < h; by += kTileRows)
    for (int bx = 0; bx < w; bx += kTileColumns) {
      Tile t{h, by, w, bx};  // empty until a needed pixel widens it
      for (int y = by; y < std::min(h, by + kTileRows); ++y)
        for (int x = bx; x < std::min(w, bx + kTileColumns); ++x)
          if (needed[static_cast<std::size_t>(y) * w + x]) {
            t.y0 = std::min(t.y0, y), t.y1 = std::max(t.y1, y + 1);
            t.x0 = std::min(t.x0, x), t.x1 = std::max(t.x1, x + 1);
          }
      if (t.y0 < t.y1) tiles.push_back(t);
    }
  return tiles;
}

// Each tile of `tiles` into `error`, in parallel.
void run_tiles(detail::SimdPath path, const Setup& s, const std::vector<Tile>& tiles,
               float* error) {
  tbb::enumerable_thread_specific<Scratch> scratch(std::min(s.width, kTileColumns), s.radius);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, tiles.size(), 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        Scratch& sc = scratch.local();
        for (std::size_t i = r.begin(); i < r.end(); ++i) tile_on(path, s, sc, tiles[i], error);
      },
      tbb::simple_partitioner());
}

// The whole map and its mean.
FlipResult whole_map(detail::SimdPath path, const Setup& s) {
  const int w = s.width, h = s.height;
  FlipResult result;
  result.error = ImageF(w, h, 1);
  run_tiles(path, s, whole_image_tiles(w, h), result.error.data.data());
  std::vector<double> row_sums(static_cast<std::size_t>(h), 0.0);
  tbb::parallel_for(0, h, [&](int y) {
    const float* row = &result.error.data[static_cast<std::size_t>(y) * w];
    double sum = 0;
    for (int x = 0; x < w; ++x) sum += row[x];
    row_sums[static_cast<std::size_t>(y)] = sum;
  });
  double total = 0;
  for (double v : row_sums) total += v;  // in row order: the same sum on any thread count
  result.mean = total / (static_cast<double>(w) * static_cast<double>(h));
  return result;
}

// The map at the needed pixels, 0 elsewhere.
ImageF map_within(detail::SimdPath path, const Setup& s, const std::vector<uint8_t>& needed) {
  ImageF map(s.width, s.height, 1);
  run_tiles(path, s, tiles_cut_to(needed, s.width, s.height), map.data.data());
  for (std::size_t p = 0; p < needed.size(); ++p)
    if (!needed[p]) map.data[p] = 0.0f;
  return map;
}

}  // namespace

FlipReference::FlipReference(const ImageF& reference, double pixels_per_degree,
                             detail::SimdPath path)
    : width_(reference.width), height_(reference.height), pixels_per_degree_(pixels_per_degree) {
  Setup s = make_setup(path, &reference, reference, pixels_per_degree);
  s.sides = Sides::ReferenceOnly;
  planes_.resize(static_cast<std::size_t>(kPreparedPlanes) * reference.pixel_count());
  s.prepared_out = planes_.data();
  run_tiles(path, s, whole_image_tiles(width_, height_), nullptr);
}

FlipResult detail::flip_on(SimdPath path, const ImageF& reference, const ImageF& test,
                           double pixels_per_degree) {
  return whole_map(path, make_setup(path, &reference, test, pixels_per_degree));
}

FlipResult detail::flip_on(SimdPath path, const FlipReference& reference, const ImageF& test) {
  return whole_map(path, make_setup(path, reference, test));
}

ImageF detail::flip_map_within_on(SimdPath path, const ImageF& reference, const ImageF& test,
                                  const std::vector<uint8_t>& needed, double pixels_per_degree) {
  return map_within(path, make_setup(path, &reference, test, pixels_per_degree), needed);
}

ImageF detail::flip_map_within_on(SimdPath path, const FlipReference& reference, const ImageF& test,
                                  const std::vector<uint8_t>& needed) {
  return map_within(path, make_setup(path, reference, test), needed);
}

int flip_radius(double pixels_per_degree) {
  return std::max(spatial_filters(pixels_per_degree).radius,
                  feature_filters(pixels_per_degree).radius);
}

ImageF flip_map_within(const ImageF& reference, const ImageF& test,
                       const std::vector<uint8_t>& needed, double pixels_per_degree) {
  return detail::flip_map_within_on(detail::widest_simd_path(), reference, test, needed,
                                    pixels_per_degree);
}

FlipResult flip(const ImageF& reference, const ImageF& test, double pixels_per_degree) {
  return detail::flip_on(detail::widest_simd_path(), reference, test, pixels_per_degree);
}

FlipResult flip(const FlipReference& reference, const ImageF& test) {
  return detail::flip_on(detail::widest_simd_path(), reference, test);
}

ImageF flip_map_within(const FlipReference& reference, const ImageF& test,
                       const std::vector<uint8_t>& needed) {
  return detail::flip_map_within_on(detail::widest_simd_path(), reference, test, needed);
}

}  // namespace sb::metrics
