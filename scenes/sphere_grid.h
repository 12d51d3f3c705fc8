#pragma once
#include "core/scene_types.h"

namespace sb {
// Forest et al. 2006's test scene: a grid of UV spheres above a ground plane
// under a square area light. Layers stack further grids above the first.
core::SceneType sphere_grid_scene_type();
// A closed UV sphere: slices × stacks, 2*slices*(stacks-1) triangles.
core::Mesh make_uv_sphere(const std::string& name, glm::vec3 center, float radius, int slices,
                          int stacks);
// A single-sided quad in the y = height plane, facing +y.
core::Mesh make_ground_plane(const std::string& name, glm::vec3 center, float half_size);
}  // namespace sb
