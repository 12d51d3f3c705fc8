#pragma once
// The uniform Monte Carlo reference's rays (internal): every covered pixel's
// spp samples, in the trace order of pixel_rays.h, 8×8 pixel tiles in
// parallel.
//
// Where the adaptive reference's proofs hold (a rectangular light, casters
// within their triangles: adaptive.h), a pixel first traces one packet (16
// samples, one corner of the light). When they agree it asks the one proof
// they allow: every ray reaches the light (sees_whole_light) after 16 lit
// samples, none does (hides_whole_light) after 16 occluded ones. A proven
// pixel's other samples would agree too (the proofs' pyramid is wider than
// the rays, far beyond float rounding), so they are not traced, and its
// value, σ (0) and stop bound are those of the full count: the image is
// the one every sample traced gives, bit for bit. The proof also settles
// the pixel's penumbra membership (settled.h), which the penumbra pass asked
// of the same proofs before.
//
// The proofs run per tile of 4×4 pixels (exact_visibility.h:
// sees_candidates, hides_candidates): when the tile's first pixel's first
// packet agrees, one walk over a shaft holding every pixel's pyramid tries
// to prove the whole tile so, and then none of its pixels traces a ray.
// Otherwise the walks' short lists of candidate triangles stand in for
// each pixel's own walk, with the same answers.
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "reference/settled.h"

namespace sb::reference {
class ExactVisibility;
}

namespace sb::reference::detail {

struct RaySetup;  // pixel_rays.h

struct UniformImages {
  core::ImageF visibility, std_error;
  // stop_rms_bound(spp) where the samples all agreed (proven or not), else 0.
  core::ImageF stop_bound;
  std::vector<Settled> settled;  // per pixel
};

// `whole_light`, when given, proves agreeing pixels (built over the same
// casters with their closed flags; only where adaptive.h's proofs hold).
UniformImages trace_uniform(const RaySetup& setup, const ExactVisibility* whole_light);

}  // namespace sb::reference::detail
