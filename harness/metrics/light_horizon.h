#pragma once
// Where each G-buffer point's tangent plane lies relative to the area light.
// It decides the one definition of V every technique shares (docs/design.md
// "One definition of V"):
//   - Above: the whole light rectangle is above the plane; V is the lit
//     fraction, and every technique is measured there;
//   - Below: the whole light is below it (attached shadow); V = 0 for every
//     technique and the reference alike;
//   - Cuts:  the plane cuts the light rectangle (the band at every curved
//     surface's terminator). The reference counts the part below the plane
//     as occluded, per sample; a technique that tests one light point cannot.
//     These pixels are left out of every other region, counted, and
//     measured on their own (the region `terminator`).
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/scene.h"

namespace sb::metrics {

enum class LightHorizon : uint8_t { Background, Above, Cuts, Below };

// `positions`: RGBA world positions, w = 0 on background; `normals`: RGB
// geometric normals facing the camera.
std::vector<LightHorizon> classify_light_horizon(const core::ImageF& positions,
                                                 const core::ImageF& normals,
                                                 const core::AreaLight& light);

// 1 where the classification equals `which`.
std::vector<uint8_t> horizon_mask(const std::vector<LightHorizon>& horizon, LightHorizon which);

}  // namespace sb::metrics
