#pragma once
// The pixel sets every job of one (scene, resolution) is measured over, and
// the mask operations that build and apply them.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/image.h"

namespace sb::metrics {

struct Regions {
  std::vector<uint8_t> measured;  // all but the pixels whose tangent plane cuts the light
  // The pixels whose tangent plane cuts the light (LightHorizon::Cuts: the
  // band at a curved surface's terminator): in no other region, measured on
  // their own (metrics/job_metrics.h); the complement of `measured`.
  std::vector<uint8_t> terminator;
  // The reference's penumbra (reference.h: Result::penumbra, the light
  // partly seen, decided exactly where the scene allows), measured ones only.
  std::vector<uint8_t> penumbra;
  std::vector<uint8_t> attached;   // the light wholly below the tangent plane: V = 0
  std::vector<uint8_t> receivers;  // measured pixels on meshes that cast no shadow
  std::vector<uint8_t> geometry;   // measured surface outside attached shadow; record "classes"
  bool any_receiver = false;
  // metrics.distance_thirds: the measured pixels by distance from the camera.
  std::optional<std::array<std::vector<uint8_t>, 3>> distance_thirds;
};

// 1 where both masks are 1.
std::vector<uint8_t> mask_and(std::vector<uint8_t> a, const std::vector<uint8_t>& b);

std::int64_t count_ones(const std::vector<uint8_t>& mask);

// Pixels whose surface faces away from every point of the light are in
// attached shadow whatever any technique says: V = 0 there for every
// technique and the reference alike, so the error measures cast shadows only.
void apply_attached_shadow(const std::vector<uint8_t>& attached, core::ImageF& visibility);

// The unmeasured pixels (mask 0) take the reference's values: they show no
// error in the heat map and in SSIM's windows.
core::ImageF with_unmeasured_from(const core::ImageF& test, const core::ImageF& ref,
                                  const std::vector<uint8_t>& measured);

// The `soft_union` region of one job: the soft pixels of its V, or the
// reference's penumbra (`regions.penumbra`, which sampling noise does not
// move), measured ones only.
std::vector<uint8_t> soft_union_of(const core::ImageF& visibility, const Regions& regions);

}  // namespace sb::metrics
