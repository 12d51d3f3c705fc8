#include "scenes/gltf_import.h"

// The import in steps, each in a file of its own: the container
// (gltf_container: GLB chunks, tinygltf), the URI sandbox (gltf_uri_sandbox:
// which files may be read), the JSON checks before tinygltf
// (gltf_json_checks), bounds-checked accessors (gltf_accessors), images and
// materials (gltf_images, gltf_materials), primitives (gltf_primitives) and
// the node hierarchy (gltf_traversal). This file runs them in that order and
// places the camera and the light from what the traversal found.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/scene_types.h"
#include "scenes/gltf_container.h"
#include "scenes/gltf_json_checks.h"
#include "scenes/gltf_traversal.h"
#include "scenes/gltf_uri_sandbox.h"

namespace sb {

using core::AreaLight;
using core::Bounds;
using core::Camera;
using core::make_area_light;
using core::Scene;

namespace {

namespace fs = std::filesystem;
using namespace gltf;

class Importer : public ImportStep {
 public:
  Importer(const std::string& file, const GltfImportOptions& options)
      : ImportStep(file), options_(options) {}

  Scene run() {
    GltfContainer container(file());
    UriSandbox sandbox(file());
    container.check_chunks();
    check_gltf_json(file(), sandbox, container.json_data(), container.json_size());
    const tg::Model model = container.parse(sandbox);
    // What the scene is built from: the file, and every buffer and image it
    // names (data: URIs are inside the file).
    scene_.inputs.push_back({file(), "", container.sha256()});
    for (const core::InputFile& f : sandbox.reads()) scene_.inputs.push_back(f);
    Traversal traversal(file(), model, scene_);
    return build(traversal);
  }

 private:
  Scene build(Traversal& traversal) {
    scene_.name = fs::path(file()).stem().string();
    traversal.run();
    const PendingCamera& pending_camera = traversal.camera();
    const PendingLight& pending_light = traversal.light();
    if (scene_.triangle_count() == 0) fail("scene", "the default scene has no triangles");

    const Bounds b = scene_.bounds();
    const glm::dvec3 center(b.center());
    const double radius = std::max(double(b.radius()), 1e-3);

    Camera& cam = scene_.camera;
    if (pending_camera.found) {
      cam.eye = glm::vec3(pending_camera.eye);
      const double d = pending_camera.distance > 0
                           ? pending_camera.distance
                           : std::max(glm::length(center - pending_camera.eye), 1e-3);
      cam.target = glm::vec3(pending_camera.eye + pending_camera.forward * d);
      cam.up = glm::vec3(pending_camera.up);
      cam.fov_y_degrees = float(glm::degrees(pending_camera.yfov));
      cam.near_plane = float(pending_camera.znear);
      double far = pending_camera.zfar;
      if (far == 0) {  // infinite: far enough for the whole scene
        far = 0;
        for (int k = 0; k < 8; ++k) {
          const glm::dvec3 corner(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y,
                                  k & 4 ? b.hi.z : b.lo.z);
          far = std::max(far, glm::length(corner - pending_camera.eye));
        }
        far = std::max(far * 1.1, pending_camera.znear * 2);
      }
      cam.far_plane = float(far);
    } else {  // frame the bounds from the front, a little above
      cam.fov_y_degrees = 45.0f;
      const double dist = radius / std::sin(glm::radians(22.5)) * 1.1;
      const glm::dvec3 eye = center + glm::normalize(glm::dvec3(0, 0.5, 1)) * dist;
      cam.eye = glm::vec3(eye);
      cam.target = glm::vec3(center);
      cam.up = glm::vec3(0, 1, 0);
      cam.near_plane = float(std::max((dist - radius) * 0.5, dist * 1e-3));
      cam.far_plane = float(dist + 2 * radius);
    }

    const double default_size = 0.05 * 2 * radius;
    AreaLight& light = scene_.light;
    glm::dvec3 lc, lt;
    double w = pending_light.width >= 0 ? pending_light.width : default_size;
    double h = pending_light.height >= 0 ? pending_light.height : default_size;
    const float intensity = float(pending_light.intensity);
    bool use_axes = false;
    bool sun = false;
    if (pending_light.found && pending_light.type == "spot") {
      lc = pending_light.position;
      const double d = pending_light.distance > 0
                           ? pending_light.distance
                           : std::max(glm::length(center - lc), 1e-3 * radius);
      lt = lc + pending_light.direction * d;
      use_axes = true;
    } else if (pending_light.found && pending_light.type == "point") {
      lc = pending_light.position;
      lt = glm::length(center - lc) > 0 ? center : lc - glm::dvec3(0, 1, 0);
    } else if (pending_light.found) {  // directional: the sun, shining along its direction
      lt = center;
      lc = center - pending_light.direction * (3 * radius);
      sun = true;
    } else {  // above the scene, like sphere_grid's light
      lt = center;
      lc = center + glm::normalize(glm::dvec3(0.35, 1, 0.25)) * (3 * radius);
    }
    light = make_area_light(glm::vec3(lc), glm::vec3(lt), float(w), float(h), intensity);
    if (sun) {
      const double degrees = pending_light.angular_diameter > 0 ? pending_light.angular_diameter
                                                                : core::kSunDiameterDegrees;
      light = core::make_sun_light(glm::vec3(lc - lt), glm::vec3(lt), float(glm::radians(degrees)),
                                   float(3 * radius), intensity);
    }
    if (use_axes) {
      // The node's x axis spans the rectangle's width (export writes it so).
      const glm::dvec3 dir = glm::normalize(lt - lc);
      glm::dvec3 u = pending_light.x_axis - dir * glm::dot(pending_light.x_axis, dir);
      if (glm::length(u) > 1e-9) {
        u = glm::normalize(u);
        const glm::dvec3 v = glm::normalize(glm::cross(u, dir));
        light.half_u = glm::vec3(u * (0.5 * w));
        light.half_v = glm::vec3(v * (0.5 * h));
      }
    }

    apply_scale();
    return std::move(scene_);
  }

  void apply_scale() {
    const float s = options_.scale;
    if (s != 1.0f) {
      for (auto& m : scene_.meshes)
        for (auto& p : m.positions) p *= s;
      AreaLight& l = scene_.light;
      l.center *= s;
      l.target *= s;
      l.half_u *= s;
      l.half_v *= s;
      Camera& c = scene_.camera;
      c.eye *= s;
      c.target *= s;
      c.near_plane *= s;
      c.far_plane *= s;
    }
    if (options_.light_size > 0) {
      AreaLight& l = scene_.light;
      const float size = options_.light_size;
      if (glm::length(l.half_u) > 0 && glm::length(l.half_v) > 0) {
        l.half_u = glm::normalize(l.half_u) * (0.5f * size);
        l.half_v = glm::normalize(l.half_v) * (0.5f * size);
      } else {
        l = make_area_light(l.center, l.target, size, size, l.intensity);
      }
    }
  }

  GltfImportOptions options_;
  Scene scene_;
};

}  // namespace

Scene load_gltf(const std::string& path, const GltfImportOptions& options) {
  return Importer(path, options).run();
}

}  // namespace sb
