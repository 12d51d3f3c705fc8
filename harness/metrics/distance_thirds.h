#pragma once
// The measured pixels split by their distance from the camera: the near,
// middle and far third of the range of distances over those pixels (equal
// distance intervals, not equal pixel counts). Perspective aliasing lives
// in the near third; a uniform shadow map spends its texels on the far one.
// On the log scale the thirds are equal intervals of log(distance), as
// cascades split a view: a street seen from eye height over a kilometre
// has nearly every pixel in the linear near third.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/image.h"

namespace sb::metrics {

enum class DistanceScale { Linear, Log };
const char* to_string(DistanceScale scale);  // "linear", "log"

// `positions`: the G-buffer's RGBA world positions (w = 0 on background,
// which belongs to no third); `measured`: one byte per pixel. Pixels at a
// boundary go to the nearer third; when every pixel lies at one distance,
// all are near. std::invalid_argument when the shapes differ.
std::array<std::vector<uint8_t>, 3> distance_thirds(const core::ImageF& positions,
                                                    const glm::vec3& eye,
                                                    const std::vector<uint8_t>& measured,
                                                    DistanceScale scale = DistanceScale::Linear);

}  // namespace sb::metrics
