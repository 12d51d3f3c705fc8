#include "planar/projected_shadow.h"

namespace sb::techniques::planar {

const char* const kProjectVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 shadow_projection;  // Blinn's M for the current light point
uniform mat4 view_projection;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[1];
};
void main() {
  vec4 q = shadow_projection * vec4(position, 1.0);
  // q.w: the vertex's height below the light along the plane's normal; the
  // part of the caster at or above the light's height is clipped away.
  gl_ClipDistance[0] = q.w;
  gl_Position = view_projection * q;
}
)";

const char* const kProjectFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D position_tex;
uniform vec4 receiver_plane;
uniform float on_plane_tolerance;
uniform float darkening_value;
out float darkening;
void main() {
  // Only G-buffer points on the receiver plane take the flattened shadow.
  vec4 p = texelFetch(position_tex, ivec2(gl_FragCoord.xy), 0);
  if (p.w == 0.0 || abs(dot(receiver_plane.xyz, p.xyz) + receiver_plane.w) > on_plane_tolerance)
    discard;
  darkening = darkening_value;
}
)";

glm::mat4 planar_projection(const glm::vec4& plane, const glm::vec3& l) {
  const glm::vec4 light(l, 1.0f);
  const float pl = glm::dot(plane, light);
  glm::mat4 m(pl);
  // glm is column-major: m[column][row]; (L πᵀ)[row][column] = L[row] π[column].
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] -= light[r] * plane[c];
  return m;
}

}  // namespace sb::techniques::planar
