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
#include "scenes/point_box_tree.h"

namespace sb {

// The plane (n, d), n·x + d = 0, of a mesh whose referenced vertices all lie
// within `eps` of it (its largest triangle gives n); nothing if not planar.
std::optional<glm::dvec4> mesh_plane(const core::Mesh& mesh, double eps);

// Whether meshes[mesh] is such a mesh (casting or not). Also the rule for a
// receiver that filtered maps may draw: nothing lies behind it. Builds the
// test below for one question: a loop over meshes makes one test instead.
bool can_shadow_nothing(const core::Scene& scene, size_t mesh);

// can_shadow_nothing for the meshes of one scene, which must outlive it and
// not change: the scene's bounds and a box tree over its vertices are made
// once, so that M planar meshes cost O(V log V) and M tree queries, not
// O(M·V) (a 200,000-node glTF of one instanced triangle took minutes in
// `validate` and `run`).
class ShadowNothingTest {
 public:
  explicit ShadowNothingTest(const core::Scene& scene);
  bool operator()(size_t mesh) const;

 private:
  const core::Scene& scene_;
  core::Bounds bounds_;
  PointBoxTree vertices_;  // every vertex an index refers to, of every mesh
};

// Marks every such casting mesh `casts_shadow = false` and returns their
// names, in scene order. Meshes that already cast nothing are not listed.
std::vector<std::string> infer_receivers(core::Scene& scene);

}  // namespace sb
