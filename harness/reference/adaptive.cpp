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
// independent of sample_uv's stream, which places the sample in that cell.
uint64_t choice_key(uint64_t seed, size_t pixel, int spp) {
  return mix64(pixel_key(seed, pixel, uint64_t(spp)) ^ 0xa0761d6478bd642full);
}

// One pixel's samples at its current level: per level cell, the fine cell
// sampled (r * fine_cols + c) and whether it reached the light.
class PixelSamples {
 public:
  PixelSamples(const Levels& levels, const std::vector<uint32_t>& order_of_cell, PixelRays& rays)
      : l_(levels), layout_(levels.layouts.back()), order_of_cell_(order_of_cell), rays_(rays) {}

  // The pilot: one random fine cell per level-0 cell, traced.
  void pilot(size_t pixel, uint64_t choice) {
    choice_ = choice;
    level_ = 0;
    rays_.start(pixel);
    const int cells = l_.cells(0);
    fine_.resize(size_t(cells));
    value_.resize(size_t(cells));
    trace_.clear();
    for (int i = 0; i < cells; ++i) {
      fine_[size_t(i)] = pick(0, i / l_.cols(0), i % l_.cols(0));
      trace_.push_back(order_of_cell_[fine_[size_t(i)]]);
    }
    rays_.trace(trace_.data(), trace_.size(), value_.data());
  }

  // Every level-k cell's sample moves to the child it lies in; the other
  // children get new samples, traced.
  void refine() {
    const int k = level_ + 1;
    const int rows = l_.rows(k), cols = l_.cols(k);
    const int br = l_.fine_rows() / rows, bc = l_.fine_cols() / cols;
    const size_t cells = size_t(rows) * size_t(cols);
    next_fine_.assign(cells, kNone);
    next_value_.assign(cells, 0);
    for (size_t i = 0; i < fine_.size(); ++i) {
      const int r = int(fine_[i]) / l_.fine_cols(), c = int(fine_[i]) % l_.fine_cols();
      const size_t child = size_t(r / br) * size_t(cols) + size_t(c / bc);
      next_fine_[child] = fine_[i];
      next_value_[child] = value_[i];
    }
    trace_.clear();
    slots_.clear();
    for (const Stratum& st : l_.layouts[size_t(k)].order) {  // 4×4 blocks of cells
      const int i = int(st.cell);
      if (next_fine_[size_t(i)] != kNone) continue;
      next_fine_[size_t(i)] = pick(k, i / cols, i % cols);
      trace_.push_back(order_of_cell_[next_fine_[size_t(i)]]);
      slots_.push_back(uint32_t(i));
    }
    reached_.resize(trace_.size());
    rays_.trace(trace_.data(), trace_.size(), reached_.data());
    for (size_t j = 0; j < slots_.size(); ++j) next_value_[slots_[j]] = reached_[j];
    fine_.swap(next_fine_);
    value_.swap(next_value_);
    level_ = k;
  }

  // Straight to level K: all spp samples, in the uniform reference's order
  // and packets (4×4 blocks of neighbouring strata, 16 rays a packet). The
  // ones already taken are traced again: a sample is a function of the pixel
  // and its index, so they come out the same, and whole coherent packets
  // cost less than packets with those samples left out (bench_reference,
  // every pixel sent to the full count: 1.26× the uniform reference's time
  // when they were left out, 1.06× with this and the tile order below).
  void refine_to_full() {
    const size_t spp = size_t(layout_.spp);
    trace_.resize(spp);
    for (size_t i = 0; i < spp; ++i) trace_[i] = uint32_t(i);
    reached_.resize(spp);
    rays_.trace(trace_.data(), spp, reached_.data());
    value_.assign(spp, 0);
    for (size_t i = 0; i < spp; ++i) value_[layout_.order[i].cell] = reached_[i];
    fine_.resize(spp);
    for (size_t c = 0; c < spp; ++c) fine_[c] = uint32_t(c);
    level_ = l_.top();
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
  // The collapsed-strata variance (reference.h) over this level's grid,
  // whose cells value_ holds in the level layout's own order.
  double variance() const { return stratified_variance(value_.data(), l_.layouts[size_t(level_)]); }

 private:
  static constexpr uint32_t kNone = 0xffffffffu;

  // A fine cell of level-k cell (row, col), at random.
  uint32_t pick(int k, int row, int col) const {
    const int br = l_.fine_rows() / l_.rows(k), bc = l_.fine_cols() / l_.cols(k);
    const uint64_t h = mix64(choice_ + (uint64_t(k) << 48) + uint64_t(row * l_.cols(k) + col) + 1);
    const int r = row * br + int((h & 0xffffffffu) % uint64_t(br));
    const int c = col * bc + int((h >> 32) % uint64_t(bc));
    return uint32_t(r * l_.fine_cols() + c);
  }

  const Levels& l_;
  const Layout& layout_;  // level K: the uniform reference's
  const std::vector<uint32_t>& order_of_cell_;
  PixelRays& rays_;
  uint64_t choice_ = 0;
  int level_ = 0;
  std::vector<uint32_t> fine_, next_fine_, trace_, slots_;
  std::vector<uint8_t> value_, next_value_, reached_;
};

enum class Pilot : uint8_t { None, Lit, Occluded, Mixed };

constexpr int kTile = 8;  // pixels a side

// The collapsed-strata error falls about as N^-3/4 in a penumbra
// (reference.h): one level, 4× the samples, divides it by about 2.83.
constexpr double kErrorFallPerLevel = 2.83;

// A pixel sent to refinement: level by level while its error is above the
// target; straight to the full count when its samples all agree (nothing
// proved them right, or a neighbour saw what they have not, and only the
// full count is sure to see it where the uniform reference does), or when
// the error's fall per level puts the target at level K anyway. The full
// count is traced in the uniform reference's coherent order. A mixed
// estimate whose error is 0 (every pair agrees, the pairs do not) is not
// trusted to meet any target.
void refine(PixelSamples& s, int top, double target) {
  while (s.level() < top) {
    if (!s.mixed()) {
      s.refine_to_full();
      return;
    }
    const double error = std::sqrt(s.variance());
    if (error > 0.0 && error <= target) return;
    const double levels_needed =
        error > 0.0 ? std::ceil(std::log(error / target) / std::log(kErrorFallPerLevel)) : 1.0;
    if (double(s.level()) + levels_needed >= double(top))
      s.refine_to_full();
    else
      s.refine();
  }
}

}  // namespace

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
  std::vector<uint32_t> order_of_cell(static_cast<size_t>(spp));
  for (size_t i = 0; i < layout.order.size(); ++i)
    order_of_cell[layout.order[i].cell] = uint32_t(i);

  const ImageF& positions = setup.positions;
  const int width = positions.width, height = positions.height;
  AdaptiveImages out{ImageF(width, height, 1, 1.0f), ImageF(width, height, 1, 0.0f),
                     ImageF(width, height, 1, 0.0f)};
  const size_t pixels = positions.pixel_count();
  std::vector<Pilot> pilot(pixels, Pilot::None);
  // Agreeing pilots proven to see the whole light, or none of it.
  std::vector<uint8_t> proven(pixels, 0);

  const auto store = [&](size_t pix, const PixelSamples& s) {
    out.visibility.data[pix] = float(double(s.reached()) / double(s.count()));
    out.std_error.data[pix] = float(std::sqrt(s.variance()));
    out.samples.data[pix] = float(s.count());
  };

  // The pilots.
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, kTile, 0, width, kTile),
                    [&](const tbb::blocked_range2d<int>& tile) {
                      FtzDazScope ftz;
                      PixelRays rays(setup);
                      PixelSamples s(levels, order_of_cell, rays);
                      for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
                        for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                          const size_t pix = size_t(y) * size_t(width) + size_t(x);
                          if (!covered(positions, pix)) continue;
                          s.pilot(pix, choice_key(setup.seed, pix, spp));
                          store(pix, s);
                          pilot[pix] = s.mixed()                  ? Pilot::Mixed
                                       : s.reached() == s.count() ? Pilot::Lit
                                                                  : Pilot::Occluded;
                          if (whole_light != nullptr && pilot[pix] != Pilot::Mixed) {
                            const float* p = &positions.data[pix * 4];
                            const glm::dvec3 surface(p[0], p[1], p[2]);
                            const glm::dvec3 origin(rays.origin()), normal(rays.normal());
                            proven[pix] =
                                pilot[pix] == Pilot::Lit
                                    ? whole_light->sees_whole_light(surface, origin, normal)
                                    : whole_light->hides_whole_light(surface, origin, normal);
                          }
                        }
                    });

  // Pixels whose window holds a covered pixel whose pilot differs from theirs.
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
  std::vector<uint8_t> taken(pixels, 0);  // queued or refined
  std::vector<size_t> work;
  for (int ty = 0; ty < height; ty += kTile)
    for (int tx = 0; tx < width; tx += kTile)
      for (int y = ty; y < std::min(ty + kTile, height); ++y)
        for (int x = tx; x < std::min(tx + kTile, width); ++x) {
          const size_t pix = size_t(y) * size_t(width) + size_t(x);
          if (pilot[pix] == Pilot::None) continue;
          const bool refine_it = pilot[pix] == Pilot::Mixed ||
                                 (whole_light != nullptr ? !proven[pix] : disagreeing_window(pix));
          if (refine_it) {
            work.push_back(pix);
            taken[pix] = 1;
          }
        }

  // Refinement rounds: a round's agreeing pixels that turn out mixed send
  // their agreeing, not yet refined neighbours to the next round.
  while (!work.empty()) {
    std::vector<uint8_t> turned_mixed(work.size(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, work.size(), 16),
                      [&](const tbb::blocked_range<size_t>& range) {
                        FtzDazScope ftz;
                        PixelRays rays(setup);
                        PixelSamples s(levels, order_of_cell, rays);
                        for (size_t w = range.begin(); w < range.end(); ++w) {
                          const size_t pix = work[w];
                          s.pilot(pix, choice_key(setup.seed, pix, spp));
                          refine(s, levels.top(), target_std_error);
                          store(pix, s);
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
          next.push_back(n);
        }
    }
    work.swap(next);
  }
  return out;
}

}  // namespace sb::reference::detail
