#pragma once
// View-dependent warps of one hard shadow map from the light's centre: the
// map is rendered and looked up through one 4×4 projective matrix, so that
// its texels fall densely where the camera looks closely.
//
// - PSM (Stamminger & Drettakis 2002): the map is a perspective view of the
//   scene in the camera's post-perspective space, from the light's image
//   there. A light behind the camera's plane has an image "beyond infinity":
//   rays from it reach the scene in reverse order, and the map's depth is
//   inverted. Casters behind the camera that can shadow what it sees are
//   brought in front of a virtual camera moved back along its axis.
// - LiSPSM (Wimmer, Scherzer & Purgathofer 2004): a perspective whose axis
//   is the view direction projected perpendicular to the light, with the
//   n_opt of the paper, applied in the light's own post-perspective space
//   (where a point light is directional).
//
// Both cover the `visible_body` (the view frustum cut to each mesh's box)
// and keep every ray from the light's centre a line along the map's depth
// axis, with depth increasing away from the light: a depth comparison in
// the warped map is the hard shadow's test.
#include <glm/glm.hpp>
#include <vector>

#include "common/light_frustum.h"
#include "core/scene.h"

namespace sb::techniques::shadow_map {

struct CameraView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
};

// What a warp did, for the record of a test or a figure.
struct WarpInfo {
  bool light_behind_camera = false;  // PSM: the inverted projection
  float virtual_shift = 0.0f;        // PSM: how far the virtual camera moved back
  bool uniform = false;              // LiSPSM: view along the light, no warp
  float n = 0.0f;                    // LiSPSM: the near distance used, in body units
};

// `view_projection` of the returned frustum is the warp; `view` and `eye`
// are the light centre's ordinary view (for the lookup's horizon test and
// its behind-the-light test). `boxes` are the scene's mesh_boxes(), made
// once per scene. With nothing visible, both fall back to
// fit_light_frustum. Throw sb::JobError where no single map can do it (PSM:
// the light's image inside the visible body, needing a cube map).
LightFrustum fit_psm(const core::Scene& scene, const std::vector<core::Bounds>& boxes,
                     const CameraView& camera, WarpInfo* info = nullptr);
// `n_scale` multiplies n_opt: larger is nearer to the uniform map.
LightFrustum fit_lispsm(const core::Scene& scene, const std::vector<core::Bounds>& boxes,
                        const CameraView& camera, float n_scale, WarpInfo* info = nullptr);

}  // namespace sb::techniques::shadow_map
