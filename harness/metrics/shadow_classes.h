#pragma once
// Lit, penumbra and umbra: each pixel's class by its visibility, and how a
// technique's classes meet the reference's (a confusion matrix). A pixel is
// umbra when V <= eps, lit when V >= 1 − eps, else penumbra: the same eps as
// penumbra_mask(). The reference's classes can come from its penumbra
// region instead (the `penumbra` region, decided exactly where the scene
// allows: reference.h), so that its sampling noise moves no pixel.
#include <array>
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace sb::metrics {

enum class ShadowClass { Lit = 0, Penumbra = 1, Umbra = 2 };

ShadowClass shadow_class(float v, float eps = 1e-6f);

// counts[reference class][technique class], over the pixels where `mask` is
// nonzero (first channel of single-channel images; std::invalid_argument
// when the shapes differ). With `reference_penumbra`, the reference's class
// is penumbra exactly where it is nonzero, elsewhere lit or umbra by the
// nearer of 1 and 0.
using ClassCounts = std::array<std::array<std::int64_t, 3>, 3>;
ClassCounts confusion_matrix(const core::ImageF& technique, const core::ImageF& reference,
                             const std::vector<uint8_t>& mask, float eps = 1e-6f,
                             const std::vector<uint8_t>* reference_penumbra = nullptr);

}  // namespace sb::metrics
