#pragma once
// Uniform draws one after another from one stream of the project's portable
// generator (core/counter_rng.h: std distributions differ between standard
// libraries, and a generated scene's seed must give the same scene
// everywhere).
#include <cstdint>

#include "core/counter_rng.h"

namespace sb {

class Draws {
 public:
  // Draws from stream `stream`, the `seed` argument of core::splitmix64.
  explicit Draws(uint64_t stream) : stream_(stream) {}
  // Uniform in [lo, hi).
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * core::uniform_float(stream_, next_++);
  }
  // True with probability p.
  bool chance(float p) { return uniform(0.0f, 1.0f) < p; }

 private:
  uint64_t stream_;
  uint64_t next_ = 0;
};

}  // namespace sb
