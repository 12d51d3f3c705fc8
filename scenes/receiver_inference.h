#pragma once
// Receivers in ordinary glTF files. glTF has no notion of a receiver: its
// ground plane is an open mesh that casts. Left so, it widens every map's
// frustum, joins every shadow ray of the reference, and stops every volume
// technique ("needs closed casters") on a scene whose objects are closed.
//
// A planar mesh can shadow nothing when the whole light lies strictly on one
// side of its plane and every other mesh lies on that side or on the plane:
// a segment between two points of one open half-space never meets the plane,
// and no point it could shadow lies on the other side. Such a mesh is made a
// non-caster. The rule is exact for every point the camera can see, which it
// also asks to be on the light's side: geometry sunk into the plane by up to
// 1/1000 of the scene's radius (roots, a model resting slightly into its
// floor) is allowed, since the plane hides it from that camera.
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace sb {

// The plane (n, d), n·x + d = 0, of a mesh whose referenced vertices all lie
// within `eps` of it (its largest triangle gives n); nothing if not planar.
std::optional<glm::dvec4> mesh_plane(const Mesh& mesh, double eps);

// Whether meshes[mesh] is such a mesh (casting or not). Also the rule for a
// receiver that filtered maps may draw: nothing lies behind it.
bool can_shadow_nothing(const Scene& scene, size_t mesh);
// The same with the scene's bounds given: a loop over every mesh computes
// them once, not once per mesh (found by tests/fuzz/fuzz_scene_spec: 600
// spheres took over 30 s in `scene info`).
bool can_shadow_nothing(const Scene& scene, size_t mesh, const Bounds& scene_bounds);

// Marks every such casting mesh `casts_shadow = false` and returns their
// names, in scene order. Meshes that already cast nothing are not listed.
std::vector<std::string> infer_receivers(Scene& scene);

}  // namespace sb
