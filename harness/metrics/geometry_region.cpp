#include "metrics/geometry_region.h"

#include <cstddef>
#include <cstring>

#include "metrics/metrics_detail.h"

namespace sb::metrics {

using core::ImageF;

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

bool matches_outside(const ImageF& test, const ImageF& ref, const std::vector<uint8_t>& region) {
  detail::check_same_shape(test, ref, "metrics::matches_outside");
  detail::check_mask(test, &region, "metrics::matches_outside");
  const size_t nc = static_cast<size_t>(test.channels);
  for (size_t p = 0; p < region.size(); ++p)
    if (!region[p] && std::memcmp(&test.data[p * nc], &ref.data[p * nc], nc * sizeof(float)) != 0)
      return false;
  return true;
}

}  // namespace sb::metrics
