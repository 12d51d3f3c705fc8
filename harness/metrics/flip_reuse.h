#pragma once
// A region's mean FLIP from maps already made.
//
// A job measures FLIP over several regions, some with a test image of their
// own (the technique's values inside the region, the reference's outside:
// job_metrics.cpp). FLIP is local: a pixel's value depends only on the
// pixels within flip_radius() of it. So where such an image equals one whose
// map is made already, on that square around a pixel, the pixel's value is
// that map's, to the bit; only the region's pixels near a difference are
// computed (flip_map_within).
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "metrics/flip.h"

namespace sb::metrics {

// A FLIP map made already: of test image `image` against the same reference.
struct KnownFlipMap {
  const core::ImageF* image;
  const core::ImageF* map;
};

// flip(reference, test)'s map at the pixels of `mask` (every pixel when
// null; 0 elsewhere), the same bits, computed only where none of `known`
// holds the value: from the known map that leaves the fewest pixels to
// compute.
core::ImageF flip_map_reusing(const FlipReference& reference, const core::ImageF& test,
                              const std::vector<uint8_t>* mask,
                              const std::vector<KnownFlipMap>& known);

}  // namespace sb::metrics
