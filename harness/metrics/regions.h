#pragma once
// The pixel sets every job of one (scene, resolution) is measured over, and
// the mask operations that build and apply them. The regions are the
// catalogue's (record::regions(), record/figures.h), in its order: each one's
// pixels are made by its entry in regions.cpp, so adding a region is its
// record entry (record/metrics_record.h) and its mask.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "metrics/distance_thirds.h"
#include "metrics/light_horizon.h"

namespace sb::metrics {

// What a region's SSIM and FLIP windows see around its pixels.
enum class Surround : std::uint8_t {
  // The technique's measured pixels (the unmeasured ones take the
  // reference's values): one SSIM pass and one FLIP map serve every such
  // region of an image.
  Technique,
  // The reference's values everywhere outside the region, so that an error
  // next to it (on the sky, say) does not count: measured on its own unless
  // the technique's values outside it already are the reference's. A region
  // of this kind with no pixel has every figure NaN and no FLIP.
  Reference,
};

// One region: its record key and its pixels (1 included).
struct RegionMask {
  std::string key;
  std::vector<uint8_t> mask;
  Surround surround = Surround::Technique;
  // Measured on the visibility against the first reference only (not the
  // shaded image, nor against a second reference).
  bool visibility_only = false;
  // Made for each job from its V (`soft_union`), not once here: `mask` is
  // empty.
  bool per_job = false;
};

struct Regions {
  // All but the pixels whose tangent plane cuts the light (the `all`
  // region's pixels): the unmeasured pixels take the reference's values.
  std::vector<uint8_t> measured;
  // The light wholly below the tangent plane: V = 0 whatever the technique.
  std::vector<uint8_t> attached;
  // In catalogue order; a region this view does not measure (no receivers,
  // no distance thirds asked for) is not in it.
  std::vector<RegionMask> masks;

  // The region called `key`; null when it is not measured here.
  const RegionMask* find(std::string_view key) const;
  // Its pixels; std::out_of_range when it is not measured here.
  const std::vector<uint8_t>& mask(std::string_view key) const;
};

// What the regions of one (scene, resolution) are made from.
struct RegionInputs {
  std::vector<LightHorizon> horizon;                     // classify_light_horizon()
  std::vector<uint8_t> reference_penumbra;               // reference::Result::penumbra
  std::vector<uint8_t> receiver;                         // 1 on meshes that cast no shadow
  const core::ImageF* positions = nullptr;               // the G-buffer's, for the distance thirds
  float eye[3] = {0, 0, 0};                              // the camera's
  bool distance_thirds = false;                          // metrics.distance_thirds
  DistanceScale distance_scale = DistanceScale::Linear;  // metrics.distance_scale
};

// Every region of the catalogue that the view has, in catalogue order.
// Throws std::logic_error for a catalogue region with no mask here.
Regions make_regions(const RegionInputs& in);

// The pixels of a region made per job (`soft_union`) for a job's V.
std::vector<uint8_t> job_mask(const RegionMask& region, const core::ImageF& visibility,
                              const Regions& regions);

// 1 where both masks are 1.
std::vector<uint8_t> mask_and(std::vector<uint8_t> a, const std::vector<uint8_t>& b);

std::int64_t count_ones(const std::vector<uint8_t>& mask);

// 1 where a 1 of `mask` (width x height) lies within `radius` pixels along x
// and along y: the mask grown by a square.
std::vector<uint8_t> dilated(const std::vector<uint8_t>& mask, int width, int height, int radius);

// True when every 1 of `inner` is a 1 of `outer`.
bool mask_within(const std::vector<uint8_t>& inner, const std::vector<uint8_t>& outer);

// Pixels whose surface faces away from every point of the light are in
// attached shadow whatever any technique says: V = 0 there for every
// technique and the reference alike, so the error measures cast shadows only.
void apply_attached_shadow(const std::vector<uint8_t>& attached, core::ImageF& visibility);

// The unmeasured pixels (mask 0) take the reference's values: they show no
// error in the heat map and in SSIM's windows.
core::ImageF with_unmeasured_from(const core::ImageF& test, const core::ImageF& ref,
                                  const std::vector<uint8_t>& measured);

// The `soft_union` region of one job: the soft pixels of its V, or the
// reference's penumbra (the `penumbra` region, which sampling noise does not
// move), measured ones only.
std::vector<uint8_t> soft_union_of(const core::ImageF& visibility, const Regions& regions);

}  // namespace sb::metrics
