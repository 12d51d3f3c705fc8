#include "metrics/geometry_region.h"

#include <cstddef>

#include "metrics/metrics_detail.h"

namespace sb::metrics {

std::vector<uint8_t> geometry_mask(const std::vector<LightHorizon>& horizon) {
  return horizon_mask(horizon, LightHorizon::Above);
}

ErrorStats compare_within(const ImageF& test, const ImageF& ref,
                          const std::vector<uint8_t>& region) {
  detail::check_same_shape(test, ref, "metrics::compare_within");
  detail::check_mask(test, &region, "metrics::compare_within");
  ImageF inside = test;
  const size_t nc = static_cast<size_t>(test.channels);
  for (size_t p = 0; p < region.size(); ++p)
    if (!region[p])
      for (size_t c = 0; c < nc; ++c) inside.data[p * nc + c] = ref.data[p * nc + c];
  return compare(inside, ref, &region);
}

}  // namespace sb::metrics
