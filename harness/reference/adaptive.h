#pragma once
// The adaptive Monte Carlo reference (reference.adaptive; internal to the
// reference, exposed for its tests).
//
// Nested strata. spp = pilot * 4^K light samples form the uniform
// reference's grid (n×n cells on a rectangle, spp cells along a segment;
// stratify.h). Level k, k = 0..K, divides the light into pilot * 4^k cells,
// each the union of a block of those fine cells: level k + 1 halves a
// level-k cell both ways (on a segment, quarters it along the segment).
// Every level-k cell holds one sample, taken in one of its fine cells chosen
// at random (per pixel, level and cell, by hash): a fine cell's sample is
// the uniform reference's own sample for that cell (pixel_rays.h), uniform
// within it, so the level-k sample is uniform within the level-k cell, the
// level-k samples are a jittered stratified sample of the light, and the
// estimate at every level is unbiased. Refining keeps each cell's sample in
// the child it fell in and draws the other three children's: at level K every
// fine cell has its own sample, and the pixel's value and standard error are
// bit-identical to the uniform reference's.
//
// Which pixels refine. Every covered pixel takes the pilot (level 0). A pilot
// whose samples disagree is refined until its collapsed-strata standard
// error (reference.h) is at most the target (an error of 0 with disagreeing
// samples is not trusted), level by level, or straight to level K when the
// error's fall per level puts the target there. A pilot whose samples all
// agree (all lit or all occluded) has an estimated error of 0 that says
// nothing about a small occluder the pilot missed. Where the casters have
// an exact polygonal form and the light is a rectangle (`whole_light`
// given), it stops only when that is proven: lit, when no caster triangle
// meets the pyramid from its ray origin to the light
// (ExactVisibility::sees_whole_light); occluded, when a closed caster
// provably covers the whole light (hides_whole_light). Every sample at any
// count then agrees, so the pilot's figures are the full count's. Otherwise
// it goes straight to level K. Without the proofs (alpha-masked or analytic
// casters, a segment light) it stops only if every covered pixel within
// kNeighbourhood pixels (a 5×5 window) has a pilot that agrees with it, all
// lit or all occluded alike; otherwise it goes to level K, and if it then
// turns out mixed it sends its own agreeing neighbours to level K in turn,
// until no more do: a penumbra that the pilots saw in one pixel is
// followed, at full samples, to wherever it fades out (an isolated soft
// pixel among agreeing ones can be missed there; the proofs cannot miss
// it). Level K is traced in the uniform reference's order (coherent
// packets).
#include <cstdint>
#include <string>

#include "core/image.h"
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
  ImageF visibility, std_error;
  ImageF samples;  // light samples taken per pixel (0 off the surfaces)
};

// The setup's layout must be make_layout(spp, strata) with spp and
// pilot_spp as adaptive_layout_problem() accepts. `whole_light`, when given,
// proves agreeing pilots (built over the same casters, with their closed
// flags; null: the window rule).
AdaptiveImages trace_adaptive(const RaySetup& setup, Strata strata, int pilot_spp,
                              double target_std_error,
                              const ExactVisibility* whole_light = nullptr);

}  // namespace sb::reference::detail
