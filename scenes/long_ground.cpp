// long_ground — posts along a long strip of ground, seen from a camera
// 1.6 units above it looking down the strip: the scene of perspective
// aliasing (Stamminger & Drettakis 2002, Wimmer et al. 2004), where a map's
// texel density matters near the camera and hardly at all far away.
//
// | parameter    | default | meaning                                                   |
// |--------------|---------|-----------------------------------------------------------|
// | length       | 60      | of the strip, from z = 4 to z = −length                   |
// | posts        | 10      | per row; two rows at x = ±1.5, the first pair at z = 3,   |
// |              |         | behind the camera, the last at z = −length + 2            |
// | light_size   | 0.06    | side of the square light: 1e-3 of the strip's length, so  |
// |              |         | that the reference is a hard shadow                       |
// | light        | side    | side: 45° up and to the −x side of the strip's middle,    |
// |              |         | shadows fall across the strip; behind: behind and above   |
// |              |         | the camera (z = 20), shadows fall along the view; front:  |
// |              |         | beyond the far end, facing the camera                     |
//
// Posts are closed boxes 0.2 × 2.5 × 0.2 standing on y = 0. The camera
// stands at (0, 1.6, 2) and looks at (0, 0.3, −length/3) with a 60° vertical
// field of view; its near plane is 0.05 and its far plane 3 × length.
#include "scenes/long_ground.h"

#include <string>
#include <utility>

#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb {

using core::choice_param;
using core::float_param;
using core::int_param;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

constexpr float kPostHalfWidth = 0.1f;
constexpr float kPostHeight = 2.5f;
constexpr float kRowOffset = 1.5f;
constexpr float kStripHalfWidth = 8.0f;

Mesh make_strip(float length) {
  Mesh m;
  m.name = "ground";
  const float near_z = 4.0f, far_z = -length;
  const float h = kStripHalfWidth;
  m.positions = {{-h, 0, far_z}, {-h, 0, near_z}, {h, 0, near_z}, {h, 0, far_z}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.casts_shadow = false;  // under everything: it occludes nothing
  m.albedo = glm::vec3(0.8f, 0.78f, 0.74f);
  return m;
}

Scene build_long_ground(const Params& p) {
  const float length = p.get_float("length");
  const int posts = p.get_int("posts");
  const float light_size = p.get_float("light_size");
  const std::string light = p.get_string("light");
  Scene s;
  s.name = "long_ground";
  // The first pair stands behind the camera (z = 3 > 2): its shadow reaches
  // the view only from a light behind the camera (PSM's virtual camera).
  const float first = 3.0f, last = -length + 2.0f;
  for (int i = 0; i < posts; ++i) {
    const float z = posts == 1 ? first : first + (last - first) * float(i) / float(posts - 1);
    for (const float x : {-kRowOffset, kRowOffset}) {
      Mesh post = make_box("post_" + std::to_string(i) + (x < 0.0f ? "_left" : "_right"),
                           glm::vec3(x, 0.5f * kPostHeight, z),
                           glm::vec3(kPostHalfWidth, 0.5f * kPostHeight, kPostHalfWidth));
      post.albedo = glm::vec3(0.55f, 0.45f, 0.40f);
      s.meshes.push_back(std::move(post));
    }
  }
  s.meshes.push_back(make_strip(length));

  const glm::vec3 middle(0.0f, 0.0f, -0.5f * length);
  if (light == "behind")
    s.light = make_area_light(glm::vec3(3.0f, 14.0f, 20.0f), glm::vec3(0.0f, 0.0f, -length / 3.0f),
                              light_size, light_size);
  else if (light == "front")
    s.light = make_area_light(glm::vec3(-3.0f, 14.0f, -length - 20.0f),
                              glm::vec3(0.0f, 0.0f, -length / 3.0f), light_size, light_size);
  else
    s.light = make_area_light(middle + glm::vec3(-0.5f * length, 0.5f * length, 0.0f), middle,
                              light_size, light_size);
  s.camera.eye = glm::vec3(0.0f, 1.6f, 2.0f);
  s.camera.target = glm::vec3(0.0f, 0.3f, -length / 3.0f);
  s.camera.fov_y_degrees = 60.0f;
  s.camera.near_plane = 0.05f;
  s.camera.far_plane = 3.0f * length;
  return s;
}

}  // namespace

SceneType long_ground_scene_type() {
  return {"long_ground",
          "posts along a long strip of ground seen from near the ground: perspective aliasing",
          {float_param("length", 60.0, 10.0, 1e4, "length of the strip"),
           int_param("posts", 10, 1, 1000, "posts per row (two rows)"),
           float_param("light_size", 0.06, 0.0, 1e4, "side of the square area light"),
           choice_param("light", "side", {"side", "behind", "front"},
                        "where the light stands: to the side of the strip, behind the camera, or "
                        "beyond the far end facing it")},
          build_long_ground,
          nullptr};
}

}  // namespace sb
