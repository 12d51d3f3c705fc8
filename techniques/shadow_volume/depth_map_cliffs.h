#pragma once
// Shadow volumes reconstructed from a depth map (McCool 2000; Rahman 2007
// §2.4): the map seen from the light's centre is a height field of the
// nearest occluders, and the boundary of the space behind it is made of the
// "cliffs" between neighbouring texels whose depths jump. Each cliff is a
// planar polygon on the plane through the light and the two texels' shared side, from
// the nearer depth down to the farther one, or past every receiver where
// the farther texel saw no occluder.
//
// The cliffs face out of the shadow (towards the farther texel), as a z-pass
// stencil count requires. Which steps are cliffs (`threshold`) is
// common/depth_cliffs.h's rule.
// The texels on a cliff's top get caps facing the light (rays can reach
// the space behind a partly covered texel through its top); elsewhere the
// occluder's own surface, in front of its texel's depth by the depth pass's
// bias, closes the volume for every ray the camera can see along.
#include <glm/glm.hpp>
#include <vector>

#include "common/light_frustum.h"

namespace sb::techniques::shadow_volume {

// `depth`: the window depths of a size×size map, row-major, row 0 at
// v = 0 (as glGetTextureImage returns them); 1 where no occluder was drawn.
// Where nothing lies behind a cliff it reaches `reach` from the light (past
// every receiver), not infinity: with a vertex at w = 0, llvmpipe's
// clipping left stray pixels counted once. Appends the cliffs' and caps'
// triangles (w = 1) to `out` and returns the number of cliffs.
size_t append_depth_map_cliffs(const std::vector<float>& depth, int size, const LightFrustum& f,
                               float threshold, float reach, std::vector<glm::vec4>& out);

}  // namespace sb::techniques::shadow_volume
