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
using flip_detail::kPt;
using flip_detail::kRgbToXyz;
using flip_detail::max_colour_distance;
using flip_detail::Scratch;
using flip_detail::Setup;
using flip_detail::spatial_filters;
using flip_detail::tile_on;

FlipResult detail::flip_on(SimdPath path, const ImageF& reference, const ImageF& test,
                           double pixels_per_degree) {
  auto channels_ok = [](const ImageF& i) {
    return i.channels == 1 || i.channels == 3 || i.channels == 4;
  };
  if (reference.width != test.width || reference.height != test.height)
    throw std::invalid_argument("flip: the images differ in size");
  if (!channels_ok(reference) || !channels_ok(test))
    throw std::invalid_argument("flip: expected 1, 3 or 4 channels");
  if (reference.pixel_count() == 0) throw std::invalid_argument("flip: empty image");
  if (!(pixels_per_degree > 0 && pixels_per_degree <= 1000))
    throw std::invalid_argument("flip: pixels per degree must be in (0, 1000], not " +
                                std::to_string(pixels_per_degree));
  if (!runs_here(path)) throw std::invalid_argument("flip: this CPU has no " + to_string(path));

  const int w = reference.width, h = reference.height;
  Setup s{{&reference, &test},
          w,
          h,
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

  FlipResult result;
  result.error = ImageF(w, h, 1);
  // Tiles of 256 columns by 128 rows: the rings fit a core's L2 cache, and
  // the first 2 radius rows each tile filters before its first output row
  // cost a sixth more of the horizontal filtering.
  constexpr int kTileColumns = 256, kTileRows = 128;
  const int columns = (w + kTileColumns - 1) / kTileColumns;
  const int tiles = columns * ((h + kTileRows - 1) / kTileRows);
  tbb::enumerable_thread_specific<Scratch> scratch(std::min(w, kTileColumns), s.radius);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles, 1),
      [&](const tbb::blocked_range<int>& r) {
        Scratch& sc = scratch.local();
        for (int i = r.begin(); i < r.end(); ++i) {
          const int x0 = (i % columns) * kTileColumns, y0 = (i / columns) * kTileRows;
          tile_on(path, s, sc,
                  {y0, std::min(h, y0 + kTileRows), x0, std::min(w, x0 + kTileColumns)},
                  result.error.data.data());
        }
      },
      tbb::simple_partitioner());
  std::vector<double> row_sums(static_cast<std::size_t>(h), 0.0);
  tbb::parallel_for(0, h, [&](int y) {
    const float* row = &result.error.data[static_cast<std::size_t>(y) * w];
    double sum = 0;
    for (int x = 0; x < w; ++x) sum += row[x];
    row_sums[static_cast<std::size_t>(y)] = sum;
  });
  double total = 0;
  for (double v : row_sums) total += v;  // in row order: the same sum on any thread count
  result.mean = total / static_cast<double>(reference.pixel_count());
  return result;
}

FlipResult flip(const ImageF& reference, const ImageF& test, double pixels_per_degree) {
  return detail::flip_on(detail::widest_simd_path(), reference, test, pixels_per_degree);
}

}  // namespace sb::metrics
