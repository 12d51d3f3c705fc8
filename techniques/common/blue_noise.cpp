#include "common/blue_noise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/counter_rng.h"

namespace sb::techniques {

namespace {

// The energy of the set pixels at every pixel: Σ exp(−d²/2σ²) over set
// pixels, d the toroidal distance. Kept up to date as pixels change.
class Energy {
 public:
  explicit Energy(int side) : side_(side), kernel_(size_t(side) * size_t(side)) {
    const double sigma = 1.5;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const int dx = std::min(x, side - x), dy = std::min(y, side - y);
        kernel_[at(x, y)] = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      }
    energy_.assign(kernel_.size(), 0.0);
  }
  void add(int i, double sign) {
    const int px = i % side_, py = i / side_;
    for (int y = 0; y < side_; ++y)
      for (int x = 0; x < side_; ++x)
        energy_[at(x, y)] += sign * kernel_[at((x - px + side_) % side_, (y - py + side_) % side_)];
  }
  size_t at(int x, int y) const { return size_t(y) * size_t(side_) + size_t(x); }
  // The set pixel of highest energy (tightest cluster) or the unset one of
  // lowest (largest void); ties to the lowest index.
  int extreme(const std::vector<char>& set, bool want_set) const {
    int best = -1;
    for (int i = 0; i < int(energy_.size()); ++i) {
      if (bool(set[size_t(i)]) != want_set) continue;
      if (best < 0 || (want_set ? energy_[size_t(i)] > energy_[size_t(best)]
                                : energy_[size_t(i)] < energy_[size_t(best)]))
        best = i;
    }
    return best;
  }

 private:
  int side_;
  std::vector<double> kernel_, energy_;
};

}  // namespace

std::vector<float> blue_noise_mask(int side, unsigned seed) {
  if (side < 4 || side > 256 || (side & (side - 1)) != 0)
    throw std::logic_error("blue_noise_mask: side " + std::to_string(side) +
                           " is not a power of two in 4..256");
  const int n = side * side;
  std::vector<char> initial(size_t(n), 0);
  int ones = 0;
  for (int i = 0; i < n; ++i)
    if (core::uniform_float(seed, uint64_t(i)) < 0.1f) {
      initial[size_t(i)] = 1;
      ++ones;
    }
  if (ones == 0) {
    initial[0] = 1;
    ones = 1;
  }
  Energy energy(side);
  for (int i = 0; i < n; ++i)
    if (initial[size_t(i)]) energy.add(i, 1.0);
  // Spread the initial points: move the tightest cluster to the largest
  // void until that would put it back.
  for (int guard = 0; guard < 10 * n; ++guard) {
    const int cluster = energy.extreme(initial, true);
    initial[size_t(cluster)] = 0;
    energy.add(cluster, -1.0);
    const int hole = energy.extreme(initial, false);
    initial[size_t(hole)] = 1;
    energy.add(hole, 1.0);
    if (hole == cluster) break;
  }
  std::vector<int> rank(size_t(n), -1);
  // Ranks below the initial count: remove the tightest cluster, last rank first.
  {
    std::vector<char> set = initial;
    Energy e = energy;
    for (int r = ones - 1; r >= 0; --r) {
      const int cluster = e.extreme(set, true);
      set[size_t(cluster)] = 0;
      e.add(cluster, -1.0);
      rank[size_t(cluster)] = r;
    }
  }
  // The rest: fill the largest void, in order.
  std::vector<char> set = initial;
  for (int r = ones; r < n; ++r) {
    const int hole = energy.extreme(set, false);
    set[size_t(hole)] = 1;
    energy.add(hole, 1.0);
    rank[size_t(hole)] = r;
  }
  std::vector<float> mask(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) mask[size_t(i)] = (float(rank[size_t(i)]) + 0.5f) / float(n);
  return mask;
}

gl::Texture make_blue_noise_texture(int side, unsigned seed) {
  const std::vector<float> mask = blue_noise_mask(side, seed);
  gl::Texture t = gl::make_texture_2d(GL_R32F, side, side);
  glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  glTextureSubImage2D(t.get(), 0, 0, 0, side, side, GL_RED, GL_FLOAT, mask.data());
  return t;
}

}  // namespace sb::techniques
