#pragma once
// Argument checks shared by the metrics sources (not part of the public API).
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace sb::metrics::detail {

// Throw std::invalid_argument naming fn when shapes or mask size disagree.
void check_same_shape(const core::ImageF& a, const core::ImageF& b, const char* fn);
void check_mask(const core::ImageF& a, const std::vector<uint8_t>* mask, const char* fn);

}  // namespace sb::metrics::detail
