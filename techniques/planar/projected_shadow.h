#pragma once
// Blinn's projected shadow (Blinn 1988), shared by planar, planar_soft and
// plateaus: caster triangles flattened onto the receiver plane from a light
// point and drawn from the camera, kept only on pixels whose G-buffer point
// lies on the plane.
#include <glm/glm.hpp>

namespace sb::techniques::planar {

// Vertex shader: `position` (location 0) through `shadow_projection` (the
// matrix below) and `view_projection`; gl_ClipDistance[0] clips the part of
// a caster at or above the light's height (planar.cpp explains why).
extern const char* const kProjectVertex;
// Fragment shader: writes `darkening_value` where the G-buffer point (unit
// 0) is within `on_plane_tolerance` of `receiver_plane`, discards elsewhere.
extern const char* const kProjectFragment;

// Blinn's projection onto n·x + d = 0 from the point l: M = (π·L) I − L πᵀ.
glm::mat4 planar_projection(const glm::vec4& plane, const glm::vec3& l);

}  // namespace sb::techniques::planar
