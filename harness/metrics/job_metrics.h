#pragma once
// A job's measured figures, as its record holds them: its visibility
// buffer's and shaded image's error against the reference's over the
// regions (record "metrics", "second_reference"), the range check of its V
// ("visibility_check") and the warning when the reference's noise is too
// large to rank it.
#include <cstdint>
#include <optional>
#include <string>

#include "core/image.h"
#include "metrics/prepared_reference.h"
#include "metrics/regions.h"
#include "record/job_record.h"
#include "record/metrics_record.h"

namespace sb::metrics {

// A technique's visibility must be finite and in [0,1]; float rounding of
// sums (accumulation, kernels) may overshoot by this much.
inline constexpr float kVisibilityTolerance = 1e-5f;  // the failure message says 1e-5

// What the check makes of one value of V.
enum class VisibilityKind : std::uint8_t { Valid, Nonfinite, Below0, Above1 };
VisibilityKind visibility_kind(float v);

// Counts each kind but Valid over V's pixels.
record::VisibilityCheckRecord check_visibility(const core::ImageF& visibility);

// The pixels check_visibility counts, by kind, as an RGB image: red (1, 0, 0)
// NaN or infinite, blue (0, 0, 1) below 0, yellow (1, 1, 0) above 1, black
// the rest (run/run_images.h writes it as invalid.png).
core::ImageF invalid_visibility_image(const core::ImageF& visibility);

// The visibility buffer's and the shaded image's error against the
// reference's (thirds included when the regions have them), FLIP at
// `flip_pixels_per_degree`, and the shaded image's whole-image FLIP
// (MetricsRecord::flip_shaded: shaded.png against the reference's, both
// decoded from sRGB as FLIP's tool reads them, every pixel, nothing
// replaced), whose map goes into *flip_map when given (one channel, in [0, 1]).
// `reference` holds the reference's V and shaded image and FLIP's viewing
// distance.
record::MetricsRecord measure(const core::ImageF& visibility, const core::ImageF& shaded,
                              const PreparedReference& reference, const Regions& regions,
                              core::ImageF* flip_map = nullptr);
// The same, preparing the reference for this one job.
record::MetricsRecord measure(const core::ImageF& visibility, const core::ImageF& shaded,
                              const core::ImageF& ref_visibility, const core::ImageF& ref_shaded,
                              const Regions& regions, double flip_pixels_per_degree,
                              core::ImageF* flip_map = nullptr);

// The visibility's error against another reference (the second one), over
// the same regions: only the reference differs. `ref_flip` is FLIP's half
// of `ref_visibility`, at the viewing distance it was made for.
record::ImageMetrics measure_visibility(const core::ImageF& visibility,
                                        const core::ImageF& ref_visibility,
                                        const FlipReference& ref_flip, const Regions& regions);

// A reference whose noise (`penumbra_rms_std_error`, reference::Result's)
// is comparable to the error cannot rank techniques.
std::optional<std::string> noise_warning(const record::MetricsRecord& m,
                                         double penumbra_rms_std_error);

}  // namespace sb::metrics
