#include "config/scene_overrides.h"

#include "config/experiment.h"
#include "core/scene_setup_check.h"

namespace sb::config {

using core::AreaLight;
using core::Camera;
using core::camera_problem;
using core::describe;
using core::fit_clip_planes;
using core::make_area_light;
using core::Scene;

using json = nlohmann::json;

void check_light(const ConfigReader& r, const json& light, const std::string& p) {
  r.object(light, p, "a light override");
  r.only_keys(light, p, {"center", "target", "size", "intensity"});
  if (light.contains("center")) r.coordinates(light["center"], p + "/center");
  if (light.contains("target")) r.coordinates(light["target"], p + "/target");
  if (light.contains("intensity")) r.positive(light["intensity"], p + "/intensity", true);
  if (light.contains("size")) {
    const json& s = light["size"];
    if (s.is_number()) {
      r.positive(s, p + "/size", true);
    } else if (s.is_array() && s.size() == 2) {
      r.positive(s[0], p + "/size/0", true);
      r.positive(s[1], p + "/size/1", true);
    } else {
      r.fail(p + "/size", "expected a number or [width, height], found " + describe(s));
    }
  }
  if (light.contains("center") && light.contains("target") &&
      r.vec3(light["center"], p + "/center") == r.vec3(light["target"], p + "/target"))
    r.fail(p + "/target", "expected a target different from the light's center");
}

void check_camera(const ConfigReader& r, const json& camera, const std::string& p) {
  r.object(camera, p, "a camera override");
  r.only_keys(camera, p, {"eye", "target", "up", "fov_y", "near", "far"});
  for (const char* k : {"eye", "target", "up"})
    if (camera.contains(k)) r.coordinates(camera[k], p + "/" + k);
  if (camera.contains("fov_y")) {
    const float f = r.positive(camera["fov_y"], p + "/fov_y", false);
    if (!(f >= 1e-3f && f < 180.0f))
      r.fail(p + "/fov_y", "expected degrees in [0.001, 180), found " + camera["fov_y"].dump());
  }
  if (camera.contains("near")) r.positive(camera["near"], p + "/near", false);
  if (camera.contains("far")) r.positive(camera["far"], p + "/far", false);
  // What the overrides alone can tell; the built scene's camera is checked
  // again whole (core/scene_setup_check.h).
  if (camera.contains("near") && camera.contains("far") &&
      !(camera["far"].get<double>() > camera["near"].get<double>()))
    r.fail(p + "/far", "expected far greater than near (" + camera["near"].dump() + "), found " +
                           camera["far"].dump());
  if (camera.contains("up") && r.vec3(camera["up"], p + "/up") == glm::vec3(0.0f))
    r.fail(p + "/up", "expected a non-zero up vector");
  if (camera.contains("eye") && camera.contains("target")) {
    Camera c;
    c.eye = r.vec3(camera["eye"], p + "/eye");
    c.target = r.vec3(camera["target"], p + "/target");
    if (camera.contains("up")) c.up = r.vec3(camera["up"], p + "/up");
    const std::string problem = camera_problem(c);
    if (!problem.empty()) r.fail(p + (camera.contains("up") ? "" : "/target"), problem);
  }
}

void apply_overrides(const SceneVariant& v, Scene& scene) {
  AreaLight& l = scene.light;
  const json& light = v.light;
  if (!light.empty()) {
    const auto vec = [](const json& a) {
      return glm::vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
    };
    const glm::vec3 center = light.contains("center") ? vec(light["center"]) : l.center;
    const glm::vec3 target = light.contains("target") ? vec(light["target"]) : l.target;
    float w = l.width(), h = l.height();
    if (light.contains("size")) {
      if (light["size"].is_number()) {
        w = h = light["size"].get<float>();
      } else {
        w = light["size"][0].get<float>();
        h = light["size"][1].get<float>();
      }
    }
    const float intensity = light.value("intensity", l.intensity);
    l = make_area_light(center, target, w, h, intensity);
  }
  const json& cam = v.camera;
  const auto vec = [](const json& a) {
    return glm::vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
  };
  if (cam.contains("eye")) scene.camera.eye = vec(cam["eye"]);
  if (cam.contains("target")) scene.camera.target = vec(cam["target"]);
  if (cam.contains("up")) scene.camera.up = vec(cam["up"]);
  if (cam.contains("fov_y")) scene.camera.fov_y_degrees = cam["fov_y"].get<float>();
  // A moved camera keeps the scene in its depth range, unless told otherwise.
  if (cam.contains("eye") || cam.contains("target")) fit_clip_planes(scene.camera, scene.bounds());
  if (cam.contains("near")) scene.camera.near_plane = cam["near"].get<float>();
  if (cam.contains("far")) scene.camera.far_plane = cam["far"].get<float>();
}

}  // namespace sb::config
