#pragma once
// The adaptive Monte Carlo reference (reference.adaptive; internal to the
// reference, exposed for its tests).
//
// Nested strata. spp = pilot * 4^K light samples form the uniform
// reference's grid (n×n cells on a rectangle, spp cells along a segment;
// stratify.h). Level k, k = 0..K, divides the light into pilot * 4^k cells,
// each the union of a block of those fine cells (on a segment, a run of
// them). A level-k sample takes one sample in every level-k cell, in one of
// its fine cells chosen at random (per pixel, stream, level and cell, by
// hash): a fine cell's sample is uniform within it, so the level-k sample is
// a jittered stratified sample of the light and its estimate is unbiased.
// At level K every fine cell has its own sample: the uniform reference's
// rays, so that a pixel estimated at the full count gets the uniform
// reference's value and standard error bit for bit.
//
// Decision and estimate are independent. Every covered pixel first traces a
// pilot, a level-0 sample from a stream of its own (PixelRays, Stream::Pilot).
// The pilot decides which level the pixel's estimate takes; the estimate is
// then a fresh level-k sample from the estimate stream, which the decision
// never saw. Given the level, its expectation is the pixel's V whatever the
// pilot said, so the choice of level cannot bias it (a level picked from the
// estimate's own samples did: stopping where those samples happened to agree
// pulled values towards 0 and 1, by up to 0.02 at target 0.1 on the sphere
// over a plane, in adaptive version 3 and before). The pilot's rays are the
// price: pilot_spp / spp of a full-count pixel's.
//
// Which level. A pilot whose samples disagree takes the level at which its
// collapsed-strata standard error (reference.h), falling about 2.83× a
// level, reaches the target (level 0 when it already does; when that error
// is 0, every pair agreeing, the unstratified binomial error stands in).
// A pilot whose samples all agree says nothing about a small occluder it
// missed. Where every caster lies within its triangles (alpha-masked ones
// do: a mask only takes parts away; analytic shapes do not) and the light
// is a rectangle (`whole_light` given), it stops only when that is proven: lit,
// when no caster triangle meets the pyramid from its ray origin to the light
// (ExactVisibility::sees_whole_light); occluded, when a closed caster
// provably covers the whole light (hides_whole_light). Every sample at any
// count then agrees, and the value is exact (standard error 0). Otherwise it
// goes to level K. Without the proofs (analytic casters, a segment light)
// it stops only if every covered pixel within kNeighbourhood
// pixels (a 5×5 window) has a pilot that agrees with it, all lit or all
// occluded alike; otherwise it goes to level K, and if that turns out mixed
// it sends its own agreeing neighbours to level K in turn, until no more do.
//
// What a stop without proof costs. A pixel whose samples all agree has no
// spread to estimate: its σ is 0 and it reports the stop bound of its sample
// count instead (stratify.h: stop_bias_bound, stop_rms_bound), whether the
// window rule stopped it at its pilot or its estimate's samples, at any
// level, all agreed. A proven pixel is exact: σ and bound 0. An estimate
// whose samples disagree reports its σ (stratify.h: standard_error).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "reference/settled.h"
#include "reference/stratify.h"

namespace sb::reference {
class ExactVisibility;
}

namespace sb::reference::detail {

struct RaySetup;  // pixel_rays.h

// The window's half side, in pixels, of the agreement test above.
inline constexpr int kNeighbourhood = 2;

// "" when spp and pilot_spp can nest (pilot_spp in {4, 16, 64}, spp =
// pilot_spp * 4^K for K >= 0), else why not.
std::string adaptive_layout_problem(int spp, int pilot_spp);

struct AdaptiveImages {
  core::ImageF visibility, std_error;
  // The stop bound of each pixel whose samples all agreed without a proof
  // (0 elsewhere).
  core::ImageF stop_bound;
  // Light samples traced per pixel, pilot included (0 off the surfaces): at
  // most spp + pilot_spp.
  core::ImageF samples;
  // Per pixel: Settled::Proven where the pilot's proof held (settled.h).
  std::vector<Settled> settled;
};

// Pixels stopped at their pilot without a proof (the window rule), as the
// images tell them: the pilot's samples only, and a stop bound above 0.
size_t unproven_stops(const core::ImageF& samples, const core::ImageF& stop_bound, int pilot_spp);

// The setup's layout must be make_layout(spp, strata) with spp and
// pilot_spp as adaptive_layout_problem() accepts. `whole_light`, when given,
// proves agreeing pilots (built over the same casters, with their closed
// flags; null: the window rule).
AdaptiveImages trace_adaptive(const RaySetup& setup, Strata strata, int pilot_spp,
                              double target_std_error,
                              const ExactVisibility* whole_light = nullptr);

}  // namespace sb::reference::detail
