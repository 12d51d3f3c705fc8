#pragma once
// FLIP's passes over the image (metrics/flip.h), one tile at a time.
//
// The image is cut into tiles: bands of rows by columns, one task each. A
// tile slides down its rows keeping, per image and per filtered quantity, a
// ring of the 2 radius + 1 rows that the vertical filters of the current row
// read, filtered horizontally as they enter. So no full-size intermediate
// plane is made: a tile's rings (about 300 KB for 256 columns) stay in its
// core's cache, where the planes (120 MB at 1920x1080) went to memory and
// page faults. Every output value is computed as before, in the same order,
// whatever the tiling, so the bits depend neither on it nor on the threads.
//
// Everything a band runs is inlined into it, and the band is compiled for
// three vector widths (baseline x86-64, AVX2, AVX-512) and picked at run
// time, as SSIM's kernels are (ssim_kernels.h); -ffp-contract=off keeps
// their bits the same.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "metrics/flip_filters.h"
#include "metrics/simd_path.h"

namespace sb::metrics::flip_detail {

// Per image: Y, Cx and the two parts of Cz (colour), the luminance's x
// derivatives and Gaussian (features), all filtered horizontally.
enum Quantity { kY, kCx, kCz1, kCz2, kDx, kDdx, kG, kQuantities };

// What FLIP computes of one image alone, per pixel, before the two are
// compared: its filtered colour in Hunt L*a*b* and its edge and point
// magnitudes. A reference's are kept as planes (FlipReference).
enum Prepared { kL, kA, kB, kEdge, kPoint, kPreparedPlanes };

// Which images a tile filters: both, making the map; the reference only,
// writing its values into `Setup::prepared_out`; or the test only, reading the
// reference's from `Setup::prepared_in`. Each image's values are the same bits either way.
enum class Sides : std::uint8_t { Both, ReferenceOnly, TestOnly };

struct Setup {
  const core::ImageF* image[2];  // the reference, the test
  int width, height;
  SpatialFilters spatial;
  FeatureFilters features;
  int radius;  // the larger filter radius: the rings' half height
  std::array<std::array<float, 3>, 3> xyz_to_rgb;
  float knee, slope_below, slope_above, feature_norm;
  Sides sides = Sides::Both;
  // kPreparedPlanes planes of width x height, plane after plane: written
  // under ReferenceOnly, read under TestOnly.
  float* prepared_out = nullptr;
  const float* prepared_in = nullptr;
};

// A thread's rows, reused from tile to tile, `width` columns wide.
class Scratch {
 public:
  Scratch(int width, int radius)
      : width_(width),
        slots_(2 * radius + 1),
        padded_(static_cast<std::size_t>(width) + 2 * static_cast<std::size_t>(radius)),
        rings_(2 * kQuantities * static_cast<std::size_t>(slots_) * width),
        pads_(4 * padded_),
        lines_(16 * static_cast<std::size_t>(width)),
        sources_(static_cast<std::size_t>(slots_)) {}
  int slots() const { return slots_; }
  float* ring(int side, int quantity, int slot) {
    return rings_.data() +
           ((static_cast<std::size_t>(side) * kQuantities + quantity) * slots_ + slot) * width_;
  }
  // The padded opponent rows of the row being filtered: Y, Cx, Cz, luminance.
  float* pad(int i) { return pads_.data() + static_cast<std::size_t>(i) * padded_; }
  // The vertical pass's output: per side Y, Cx, Cz1, Cz2, dx, ddx, dy, ddy.
  float* line(int i) { return lines_.data() + static_cast<std::size_t>(i) * width_; }
  // A filter's source rows, one per tap.
  const float** sources() { return sources_.data(); }

 private:
  int width_, slots_;
  std::size_t padded_;
  std::vector<float> rings_, pads_, lines_;
  std::vector<const float*> sources_;
};

// A tile's rows and columns.
struct Tile {
  int y0, y1, x0, x1;
};

// FLIP of tile `t` into `error` (the whole map, `s.width` wide; null under
// ReferenceOnly), on the
// given vector width (which this CPU must run).
void tile_on(detail::SimdPath path, const Setup& s, Scratch& sc, const Tile& t, float* error);

}  // namespace sb::metrics::flip_detail
