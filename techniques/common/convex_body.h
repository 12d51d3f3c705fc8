#pragma once
// A convex polytope as its face polygons, clipped by planes: the "body" of
// space a view-dependent shadow map must cover (the view frustum cut to the
// scene's boxes, Wimmer et al. 2004's B). Only its vertices are read: the
// extremes of a linear or projective function with positive w over a convex
// polytope lie at its vertices.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed): plain
// CPU code (no GL), in world units (or whatever space the planes and boxes
// share); clip() costs O(vertices) per plane, visible_body() 6 clips per box.
#include <glm/glm.hpp>
#include <vector>

#include "core/scene.h"

namespace sb::techniques {

// A convex polytope as face polygons: box() makes one, clip() cuts it by a
// plane, vertices() lists the corners.
// units: those of the box and planes (world units in the kit).
// cost: clip() O(vertices) per plane; no GL.
class ConvexBody {
 public:
  static ConvexBody box(const core::Bounds& b);
  // Keeps the half-space dot(plane.xyz, p) + plane.w >= 0.
  void clip(const glm::vec4& plane);
  bool empty() const { return faces_.empty(); }
  // Every face corner (shared corners repeat).
  std::vector<glm::vec3> vertices() const;

 private:
  std::vector<std::vector<glm::vec3>> faces_;
};

// The six planes of the clip-space frustum of `view_projection`, each facing
// inwards (Gribb & Hartmann 2001): the points with -w <= x, y, z <= w.
std::vector<glm::vec4> frustum_planes(const glm::mat4& view_projection);

// Each mesh's bounding box (of all its positions), in Scene::meshes order:
// scene data that no light or camera moves, computed once per scene.
std::vector<core::Bounds> mesh_boxes(const core::Scene& scene);

// The vertices of the union of `boxes` (mesh_boxes()) each cut to `planes`:
// what the camera can see of the scene, tighter than one box around
// everything (a ground and a far post leave the space between them out of
// the near and far depths). Empty when nothing is inside.
std::vector<glm::vec3> visible_body(const std::vector<core::Bounds>& boxes,
                                    const std::vector<glm::vec4>& planes);

}  // namespace sb::techniques
