#pragma once
// Leaves: a procedurally drawn leaf mask and the alpha-tested quads that use
// it. Thin, double-sided, open occluders: the hard case for shadow volumes
// and the reason every caster pass and the reference honour alpha masks.
#include <cstdint>

#include "core/scene.h"

namespace sb {

// A size×size RGBA leaf: a pointed blade along v with a short stalk at
// v = 0, alpha 255 inside and 0 outside, green with a lighter midrib.
core::TextureImage make_leaf_texture(int size, uint32_t seed);

// Share of the leaf texture's texels that are opaque (alpha >= cutoff).
double opaque_fraction(const core::TextureImage& texture, float cutoff);

// One alpha-tested, double-sided quad: corners center ± half_u ± half_v, uv
// (0,0) at center - half_u - half_v, v running along half_v.
core::Mesh make_leaf_quad(const std::string& name, glm::vec3 center, glm::vec3 half_u,
                          glm::vec3 half_v, int texture);

}  // namespace sb
