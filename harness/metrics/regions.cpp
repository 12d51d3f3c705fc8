#include "metrics/regions.h"

#include <algorithm>

#include "metrics/metrics.h"

namespace sb::metrics {

using core::ImageF;

std::vector<uint8_t> mask_and(std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
  for (size_t i = 0; i < a.size(); ++i) a[i] = a[i] && b[i] ? 1 : 0;
  return a;
}

std::int64_t count_ones(const std::vector<uint8_t>& mask) {
  return std::count(mask.begin(), mask.end(), uint8_t(1));
}

void apply_attached_shadow(const std::vector<uint8_t>& attached, ImageF& visibility) {
  for (size_t i = 0; i < attached.size(); ++i)
    if (attached[i]) visibility.data[i] = 0.0f;
}

ImageF with_unmeasured_from(const ImageF& test, const ImageF& ref,
                            const std::vector<uint8_t>& measured) {
  ImageF out = test;
  for (size_t i = 0; i < measured.size(); ++i)
    if (!measured[i])
      for (int c = 0; c < out.channels; ++c)
        out.data[i * size_t(out.channels) + size_t(c)] =
            ref.data[i * size_t(ref.channels) + size_t(c)];
  return out;
}

std::vector<uint8_t> soft_union_of(const ImageF& visibility, const Regions& regions) {
  std::vector<uint8_t> mask = penumbra_mask(visibility);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = uint8_t(mask[i] | regions.penumbra[i]);
  return mask_and(std::move(mask), regions.measured);
}

}  // namespace sb::metrics
