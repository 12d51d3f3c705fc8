#include "config/scene_overrides.h"

#include <algorithm>

#include "config/experiment.h"
#include "core/scene_setup_check.h"
#include "core/scene_types.h"

namespace sb::config {

using core::AreaLight;
using core::Camera;
using core::camera_problem;
using core::describe;
using core::fit_clip_planes;
using core::make_area_light;
using core::make_sun_light;
using core::Scene;

using json = nlohmann::json;

namespace {

bool is_sun_override(const json& light) {
  return light.contains("type") && light["type"].is_string() && light["type"] == "sun";
}

// The sun's angular diameter in degrees: above 0 (a sun of no size is a
// hard light, which no reference below 1e-4° can tell from 0), under 90.
void check_sun_diameter(const ConfigReader& r, const json& d, const std::string& p) {
  const float degrees = r.positive(d, p, false);
  if (!(degrees >= 1e-4f && degrees <= 90.0f))
    r.fail(p, "expected the sun's angular diameter in degrees in [0.0001, 90], found " + d.dump());
}

}  // namespace

void check_light(const ConfigReader& r, const json& light, const std::string& p) {
  r.object(light, p, "a light override");
  if (light.contains("type")) {
    const json& t = light["type"];
    if (!t.is_string() || (t != "rectangle" && t != "sun"))
      r.fail(p + "/type", "expected \"rectangle\" or \"sun\", found " + describe(t));
  }
  if (is_sun_override(light)) {
    r.only_keys(light, p, {"type", "direction", "angular_diameter", "target", "intensity"});
    if (light.contains("direction")) {
      r.coordinates(light["direction"], p + "/direction");
      if (r.vec3(light["direction"], p + "/direction") == glm::vec3(0.0f))
        r.fail(p + "/direction", "expected a non-zero direction towards the sun");
    }
    if (light.contains("angular_diameter"))
      check_sun_diameter(r, light["angular_diameter"], p + "/angular_diameter");
    if (light.contains("target")) r.coordinates(light["target"], p + "/target");
    if (light.contains("intensity")) r.positive(light["intensity"], p + "/intensity", true);
    return;
  }
  r.only_keys(light, p, {"type", "center", "target", "size", "intensity"});
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

namespace {

glm::vec3 vec3_of(const json& a) {
  return {a[0].get<float>(), a[1].get<float>(), a[2].get<float>()};
}

// The sun: from the override's direction, or the scene's light's; aimed at
// the override's target or the scene's light's; 3 bounding radii away (a
// place for code that wants one: the references put the sun at infinity).
AreaLight sun_from(const json& light, const AreaLight& was, const Scene& scene) {
  const glm::vec3 target = light.contains("target") ? vec3_of(light["target"]) : was.target;
  const glm::vec3 to_sun = light.contains("direction") ? vec3_of(light["direction"]) : was.to_sun();
  const float degrees = light.contains("angular_diameter") ? light["angular_diameter"].get<float>()
                        : was.is_sun()                     ? glm::degrees(was.angular_diameter)
                                                           : core::kSunDiameterDegrees;
  const float distance = std::max(
      3.0f * scene.bounds().radius() + glm::length(target - scene.bounds().center()), 1e-3f);
  return make_sun_light(to_sun, target, glm::radians(degrees), distance,
                        light.value("intensity", was.intensity));
}

}  // namespace

void apply_overrides(const SceneVariant& v, Scene& scene) {
  AreaLight& l = scene.light;
  const json& light = v.light;
  // A sun stays one unless the override makes it a rectangle (a type, a
  // center or a size).
  const bool stays_sun =
      l.is_sun() && !light.contains("type") && !light.contains("center") && !light.contains("size");
  if (is_sun_override(light) || (stays_sun && !light.empty())) {
    l = sun_from(light, l, scene);
  } else if (!light.empty()) {
    const auto vec = [](const json& a) { return vec3_of(a); };
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
