#include "metrics/shadow_classes.h"

#include <stdexcept>

namespace sb::metrics {

using core::ImageF;

ShadowClass shadow_class(float v, float eps) {
  if (v <= eps) return ShadowClass::Umbra;
  if (v >= 1.0f - eps) return ShadowClass::Lit;
  return ShadowClass::Penumbra;  // NaN too: neither lit nor umbra
}

ClassCounts confusion_matrix(const ImageF& technique, const ImageF& reference,
                             const std::vector<uint8_t>& mask, float eps,
                             const std::vector<uint8_t>* reference_penumbra) {
  if (!technique.same_shape(reference) || technique.channels != 1 ||
      mask.size() != technique.pixel_count() ||
      (reference_penumbra != nullptr && reference_penumbra->size() != mask.size()))
    throw std::invalid_argument("confusion_matrix: images and mask differ in shape");
  ClassCounts counts{};
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    const float v = reference.data[i];
    const ShadowClass reference_class = reference_penumbra == nullptr ? shadow_class(v, eps)
                                        : (*reference_penumbra)[i]    ? ShadowClass::Penumbra
                                        : v >= 0.5f                   ? ShadowClass::Lit
                                                                      : ShadowClass::Umbra;
    const auto r = static_cast<size_t>(reference_class);
    const auto t = static_cast<size_t>(shadow_class(technique.data[i], eps));
    ++counts[r][t];
  }
  return counts;
}

}  // namespace sb::metrics
