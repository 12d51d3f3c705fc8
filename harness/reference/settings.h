#pragma once
// What a reference is asked for (reference.h computes it): plain data, so
// that a config can hold it without the reference's dependencies.
#include <cstdint>
#include <string>
#include <utility>

namespace sb::reference {

// The most samples per pixel a reference takes (spp, and an adaptive
// reference's pilot_spp): the config's bound, checked again by the reference.
inline constexpr int kMaxSpp = 1 << 20;

struct Settings {
  Settings(int spp_ = 256, uint64_t seed_ = 1, std::string embree_config_ = "")
      : spp(spp_), seed(seed_), embree_config(std::move(embree_config_)) {}
  int spp;  // at least 1; with 1 there is no pair to estimate the error from
  uint64_t seed;
  // Embree's device config: "isa=NAME" or "max_isa=NAME" (embree_isa.h);
  // empty: default_embree_config(), i.e. the environment's or the best ISA.
  std::string embree_config;
  // The exact reference (exact_visibility.h) instead of sampling: V without
  // noise, std_error 0, spp 0. A scene it cannot do (alpha masks, analytic
  // shapes, a point light) gets the Monte Carlo reference, and
  // Result::exact_fallback says why.
  bool exact = false;
  // Adaptive sampling (adaptive.h): a pilot of pilot_spp samples per pixel
  // decides how many fresh samples, up to spp (which must be
  // pilot_spp * 4^K), the pixel's estimate takes: the level planned to bring
  // its standard error to target_std_error, or spp where an agreeing pilot
  // is not proven (or, without proofs, its neighbourhood disagrees).
  bool adaptive = false;
  int pilot_spp = 4;
  double target_std_error = 0.01;
};

}  // namespace sb::reference
