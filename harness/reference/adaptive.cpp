#include "reference/adaptive.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "reference/embree_scene.h"
#include "reference/exact_visibility.h"
#include "reference/pixel_rays.h"

namespace sb::reference::detail {

using core::ImageF;

namespace {

// The levels of one layout: level k is make_layout(pilot * 4^k) (stratify.h),
// a grid of rows(k) × cols(k) cells, row-major, whose trace order already
// takes its cells in 4×4 blocks and whose groups are the neighbour pairs of
// the standard error; level K is the uniform reference's own layout.
struct Levels {
  std::vector<Layout> layouts;
  int top() const { return int(layouts.size()) - 1; }
  int rows(int k) const { return layouts[size_t(k)].rows; }
  int cols(int k) const { return layouts[size_t(k)].spp / rows(k); }
  int cells(int k) const { return layouts[size_t(k)].spp; }
  int fine_rows() const { return rows(top()); }
  int fine_cols() const { return cols(top()); }
};

bool power_of_four_times(int spp, int pilot) {
  if (pilot <= 0 || spp < pilot || spp % pilot != 0) return false;
  for (int q = spp / pilot; q > 1; q /= 4)
    if (q % 4 != 0) return false;
  return true;
}

Levels levels_of(int spp, int pilot, Strata strata) {
  Levels l;
  for (int cells = pilot; cells <= spp; cells *= 4) l.layouts.push_back(make_layout(cells, strata));
  return l;
}

// The per-pixel stream that picks which fine cell of a cell is sampled:
// independent of sample_uv's stream, which places the sample in that cell,
// and of the other Stream's.
uint64_t choice_key(uint64_t seed, size_t pixel, int spp, Stream stream) {
  const uint64_t k = mix64(pixel_key(seed, pixel, uint64_t(spp)) ^ 0xa0761d6478bd642full);
  return stream == Stream::Pilot ? mix64(k ^ 0xe7037ed1a0b428dbull) : k;
}

// One pixel's level-k sample: per level-k cell, whether its sample reached
// the light, indexed by cell (row-major).
class LevelSample {
 public:
  LevelSample(const Levels& levels, const std::vector<uint32_t>& order_of_cell, PixelRays& rays)
      : l_(levels), order_of_cell_(order_of_cell), rays_(rays) {}

  // Below level K, one random fine cell per level-k cell, traced in the
  // level layout's order (4×4 blocks of cells, coherent packets). At level K
  // every fine cell, in the uniform reference's order and packets: its very
  // rays.
  void trace(size_t pixel, uint64_t seed, int k, Stream stream) {
    level_ = k;
    rays_.start(pixel, stream);
    const Layout& layout = l_.layouts[size_t(k)];
    const size_t cells = size_t(layout.spp);
    trace_.resize(cells);
    if (k == l_.top()) {
      for (size_t i = 0; i < cells; ++i) trace_[i] = uint32_t(i);
    } else {
      const uint64_t choice = choice_key(seed, pixel, l_.layouts.back().spp, stream);
      for (size_t i = 0; i < cells; ++i) {
        const int cell = int(layout.order[i].cell);
        trace_[i] = order_of_cell_[pick(choice, k, cell / l_.cols(k), cell % l_.cols(k))];
      }
    }
    reached_.resize(cells);
    rays_.trace(trace_.data(), cells, reached_.data());
    value_.resize(cells);
    for (size_t i = 0; i < cells; ++i) value_[layout.order[i].cell] = reached_[i];
  }

  int level() const { return level_; }
  size_t count() const { return value_.size(); }
  size_t reached() const {
    size_t n = 0;
    for (uint8_t v : value_) n += v;
    return n;
  }
  bool mixed() const {
    const size_t n = reached();
    return n != 0 && n != value_.size();
  }
  double mean() const { return double(reached()) / double(count()); }
  // σ over this level's grid (stratify.h): 0 when every sample agrees.
  double standard_error() const {
    return detail::standard_error(value_.data(), l_.layouts[size_t(level_)]);
  }

 private:
  // A fine cell of level-k cell (row, col), at random.
  uint32_t pick(uint64_t choice, int k, int row, int col) const {
    const int br = l_.fine_rows() / l_.rows(k), bc = l_.fine_cols() / l_.cols(k);
    const uint64_t h = mix64(choice + (uint64_t(k) << 48) + uint64_t(row * l_.cols(k) + col) + 1);
    const int r = row * br + int((h & 0xffffffffu) % uint64_t(br));
    const int c = col * bc + int((h >> 32) % uint64_t(bc));
    return uint32_t(r * l_.fine_cols() + c);
  }

  const Levels& l_;
  const std::vector<uint32_t>& order_of_cell_;
  PixelRays& rays_;
  int level_ = 0;
  std::vector<uint32_t> trace_;
  std::vector<uint8_t> value_, reached_;
};

enum class Pilot : uint8_t { None, Lit, Occluded, Mixed };

constexpr int kTile = 8;  // pixels a side

// The collapsed-strata error falls about as N^-3/4 in a penumbra
// (reference.h): one level, 4× the samples, divides it by about 2.83.
constexpr double kErrorFallPerLevel = 2.83;

// The level a disagreeing pilot sends its pixel's estimate to: where its
// error (stratify.h: standard_error, never 0 for disagreeing samples),
// falling kErrorFallPerLevel a level, reaches the target.
int planned_level(const LevelSample& pilot, int top, double target) {
  const double error = pilot.standard_error();
  if (error <= target) return 0;
  const double levels = std::ceil(std::log(error / target) / std::log(kErrorFallPerLevel));
  return levels >= double(top) ? top : int(levels);
}

}  // namespace

size_t unproven_stops(const ImageF& samples, const ImageF& stop_bound, int pilot_spp) {
  size_t n = 0;
  for (size_t i = 0; i < samples.data.size(); ++i)
    n += samples.data[i] == float(pilot_spp) && stop_bound.data[i] > 0.0f ? 1 : 0;
  return n;
}

std::string adaptive_layout_problem(int spp, int pilot_spp) {
  if (pilot_spp != 4 && pilot_spp != 16 && pilot_spp != 64)
    return "the pilot must be 4, 16 or 64 samples, got " + std::to_string(pilot_spp);
  if (!power_of_four_times(spp, pilot_spp))
    return "spp must be the pilot's " + std::to_string(pilot_spp) +
           " samples times a power of 4 (" + std::to_string(pilot_spp) + ", " +
           std::to_string(pilot_spp * 4) + ", " + std::to_string(pilot_spp * 16) + ", " +
           std::to_string(pilot_spp * 64) + ", ...), got " + std::to_string(spp);
  return "";
}

AdaptiveImages trace_adaptive(const RaySetup& setup, Strata strata, int pilot_spp,
                              double target_std_error, const ExactVisibility* whole_light) {
  const Layout& layout = setup.layout;
  const int spp = layout.spp;
  if (const std::string why = adaptive_layout_problem(spp, pilot_spp); !why.empty())
    throw std::invalid_argument("reference: adaptive sampling: " + why);
  const Levels levels = levels_of(spp, pilot_spp, strata);
  const int top = levels.top();
  std::vector<uint32_t> order_of_cell(static_cast<size_t>(spp));
  for (size_t i = 0; i < layout.order.size(); ++i)
    order_of_cell[layout.order[i].cell] = uint32_t(i);

  const ImageF& positions = setup.positions;
  const int width = positions.width, height = positions.height;
  AdaptiveImages out{ImageF(width, height, 1, 1.0f),
                     ImageF(width, height, 1, 0.0f),
                     ImageF(width, height, 1, 0.0f),
                     ImageF(width, height, 1, 0.0f),
                     {}};
  const size_t pixels = positions.pixel_count();
  std::vector<Pilot> pilot(pixels, Pilot::None);
  // The level each pixel's estimate takes; -1: it stops at its pilot.
  std::vector<int8_t> level(pixels, -1);
  // Agreeing pilots proven to see the whole light, or none of it.
  std::vector<uint8_t> proven(pixels, 0);
  const float unproven_error = float(stop_rms_bound(pilot_spp));

  // The pilots: they decide, and stand as the value only where they agree.
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, kTile, 0, width, kTile),
                    [&](const tbb::blocked_range2d<int>& tile) {
                      FtzDazScope ftz;
                      PixelRays rays(setup);
                      LevelSample s(levels, order_of_cell, rays);
                      for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
                        for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                          const size_t pix = size_t(y) * size_t(width) + size_t(x);
                          if (!covered(positions, pix)) continue;
                          s.trace(pix, setup.seed, 0, Stream::Pilot);
                          out.samples.data[pix] = float(s.count());
                          if (s.mixed()) {
                            pilot[pix] = Pilot::Mixed;
                            level[pix] = int8_t(planned_level(s, top, target_std_error));
                            continue;
                          }
                          pilot[pix] = s.reached() == s.count() ? Pilot::Lit : Pilot::Occluded;
                          out.visibility.data[pix] = pilot[pix] == Pilot::Lit ? 1.0f : 0.0f;
                          if (whole_light != nullptr) {
                            const float* p = &positions.data[pix * 4];
                            const glm::dvec3 surface(p[0], p[1], p[2]);
                            const glm::dvec3 origin(rays.origin()), normal(rays.normal());
                            proven[pix] =
                                pilot[pix] == Pilot::Lit
                                    ? whole_light->sees_whole_light(surface, origin, normal)
                                    : whole_light->hides_whole_light(surface, origin, normal);
                          }
                          // A stop without proof reports the error such stops can hide.
                          out.stop_bound.data[pix] = proven[pix] ? 0.0f : unproven_error;
                        }
                    });

  // Agreeing pilots not proven go to the full count where proofs exist,
  // and under the window rule where a covered pixel in their window has a
  // pilot unlike theirs.
  const auto disagreeing_window = [&](size_t pix) {
    const int x = int(pix % size_t(width)), y = int(pix / size_t(width));
    for (int dy = -kNeighbourhood; dy <= kNeighbourhood; ++dy)
      for (int dx = -kNeighbourhood; dx <= kNeighbourhood; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        const Pilot p = pilot[size_t(ny) * size_t(width) + size_t(nx)];
        if (p != Pilot::None && p != pilot[pix]) return true;
      }
    return false;
  };
  // Queued in 8×8 tiles, as the uniform reference traces its pixels:
  // neighbouring pixels' rays meet the same casters.
  std::vector<uint8_t> taken(pixels, 0);  // queued or estimated
  std::vector<size_t> work;
  for (int ty = 0; ty < height; ty += kTile)
    for (int tx = 0; tx < width; tx += kTile)
      for (int y = ty; y < std::min(ty + kTile, height); ++y)
        for (int x = tx; x < std::min(tx + kTile, width); ++x) {
          const size_t pix = size_t(y) * size_t(width) + size_t(x);
          if (pilot[pix] == Pilot::None) continue;
          if (pilot[pix] != Pilot::Mixed && !proven[pix] &&
              (whole_light != nullptr || disagreeing_window(pix)))
            level[pix] = int8_t(top);
          if (level[pix] >= 0) {
            work.push_back(pix);
            taken[pix] = 1;
          }
        }

  // The estimates, fresh samples at the level decided. A round's agreeing
  // pilots whose estimate turns out mixed send their agreeing, not yet
  // estimated neighbours to the next round, at the full count.
  while (!work.empty()) {
    std::vector<uint8_t> turned_mixed(work.size(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, work.size(), 16),
                      [&](const tbb::blocked_range<size_t>& range) {
                        FtzDazScope ftz;
                        PixelRays rays(setup);
                        LevelSample s(levels, order_of_cell, rays);
                        for (size_t w = range.begin(); w < range.end(); ++w) {
                          const size_t pix = work[w];
                          s.trace(pix, setup.seed, level[pix], Stream::Estimate);
                          out.visibility.data[pix] = float(s.mean());
                          out.std_error.data[pix] = float(s.standard_error());
                          out.stop_bound.data[pix] =
                              s.mixed() ? 0.0f : float(stop_rms_bound(int(s.count())));
                          out.samples.data[pix] = float(pilot_spp) + float(s.count());
                          turned_mixed[w] = pilot[pix] != Pilot::Mixed && s.mixed() ? 1 : 0;
                        }
                      });
    std::vector<size_t> next;
    for (size_t w = 0; w < work.size(); ++w) {
      if (!turned_mixed[w]) continue;
      const int x = int(work[w] % size_t(width)), y = int(work[w] / size_t(width));
      for (int dy = -kNeighbourhood; dy <= kNeighbourhood; ++dy)
        for (int dx = -kNeighbourhood; dx <= kNeighbourhood; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t n = size_t(ny) * size_t(width) + size_t(nx);
          if (pilot[n] == Pilot::None || taken[n] || proven[n]) continue;
          taken[n] = 1;
          level[n] = int8_t(top);
          next.push_back(n);
        }
    }
    work.swap(next);
  }
  out.settled.assign(pixels, Settled::Unknown);
  for (size_t pix = 0; pix < pixels; ++pix)
    if (proven[pix]) out.settled[pix] = Settled::Proven;
  return out;
}

}  // namespace sb::reference::detail
