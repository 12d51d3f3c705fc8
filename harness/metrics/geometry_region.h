#pragma once
// The `geometry` region: the measured surface pixels outside attached shadow,
// i.e. the pixels whose tangent plane has the whole light above it
// (LightHorizon::Above). Sky, attached shadow (V = 0 for every technique by
// rule) and the horizon-cut band (measured on its own, `terminator`) are not in it, so
// its error does not change with how much of the frame they fill: the region
// to compare techniques and scenes by (docs/results.md, "Regions").
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"

namespace sb::metrics {

// 1 on the geometry region's pixels.
std::vector<uint8_t> geometry_mask(const std::vector<LightHorizon>& horizon);

// compare(test, ref, &region) after every pixel outside `region` took ref's
// values: the outside is not the technique's to get wrong, so an SSIM window
// that reaches past the region's edge (into the sky, say) sees no error from
// there. Every figure but SSIM equals compare(test, ref, &region); SSIM is the
// mean of that map over the region's pixels at least kSsimRadius from every
// border.
ErrorStats compare_within(const core::ImageF& test, const core::ImageF& ref,
                          const std::vector<uint8_t>& region);

// True when every value outside `region` is bit for bit the same in test and
// ref: then compare_within(test, ref, region) == compare(test, ref, &region),
// and the region can share the other masks' SSIM pass (metrics.h). So it is
// for any technique that writes V = 1 on the sky, and for every shaded image.
bool matches_outside(const core::ImageF& test, const core::ImageF& ref,
                     const std::vector<uint8_t>& region);

}  // namespace sb::metrics
