#pragma once
// The default scene's node hierarchy. It is checked to be a forest (every
// node has at most one parent, no cycles, roots are no one's child), walked
// depth-first in file order without recursion (hierarchies can be deep),
// and each mesh node is instanced in world space: vertices transformed (a
// mirroring transform flips the winding, a zero scale drops the node),
// normals by the inverse transpose, flat normals made where the mesh has
// none. The first perspective camera and the first KHR_lights_punctual
// light met on the way are kept, with their world transforms, for the
// importer to place.
#include <string>
#include <vector>

#include "core/scene.h"
#include "scenes/gltf_common.h"
#include "scenes/gltf_primitives.h"

namespace sb::gltf {

struct PendingCamera {
  bool found = false;
  glm::dvec3 eye, forward, up;
  double yfov = 0, znear = 0, zfar = 0, distance = 0;  // zfar 0: infinite
};

struct PendingLight {
  bool found = false;
  std::string type;
  glm::dvec3 position, direction, x_axis;
  double width = -1, height = -1, intensity = 1, distance = 0;
  double angular_diameter = -1;  // degrees, a directional light's (-1: the default)
};

class Traversal : public ImportStep {
 public:
  // Meshes, textures and the ambient colour go into `scene`.
  Traversal(const std::string& file, const tg::Model& model, core::Scene& scene)
      : ImportStep(file), model_(model), scene_(scene), primitives_(file, model, scene.textures) {}
  void run();
  const PendingCamera& camera() const { return camera_; }
  const PendingLight& light() const { return light_; }

 private:
  std::vector<int> check_hierarchy() const;
  glm::dmat4 local_matrix(const tg::Node& n, const std::string& where) const;
  void instantiate(size_t node_index, const glm::dmat4& world);
  void visit_camera(size_t node_index, const glm::dmat4& world);
  bool visit_light(size_t node_index, const glm::dmat4& world);

  const tg::Model& model_;
  core::Scene& scene_;
  PrimitiveLoader primitives_;
  size_t total_triangles_ = 0;
  PendingCamera camera_;
  PendingLight light_;
};

}  // namespace sb::gltf
