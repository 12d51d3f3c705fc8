#include "core/scene_types.h"

#include <cmath>
#include <stdexcept>

#include "scenes/foliage.h"
#include "scenes/gltf_scene_type.h"
#include "scenes/jeep.h"
#include "scenes/long_ground.h"
#include "scenes/outdoor.h"
#include "scenes/plates.h"
#include "scenes/sphere_grid.h"
#include "scenes/standing.h"
#include "scenes/stress_geometry.h"

namespace sb {

// core/scene_types.h's registry, which knows the scene types of scenes/.
using core::AreaLight;
using core::SceneType;

namespace {
std::vector<SceneType>& registry() {
  static std::vector<SceneType> types = {
      sphere_grid_scene_type(), foliage_scene_type(),         jeep_scene_type(),
      plates_scene_type(),      stress_geometry_scene_type(), standing_scene_type(),
      long_ground_scene_type(), outdoor_scene_type(),         gltf_scene_type(),
  };
  return types;
}
}  // namespace

const std::vector<SceneType>& core::scene_types() { return registry(); }

void core::add_scene_type(SceneType type) {
  if (find_scene_type(type.name) != nullptr)
    throw std::logic_error("scene type '" + type.name + "' registered twice");
  registry().push_back(std::move(type));
}

const SceneType* core::find_scene_type(const std::string& name) {
  for (const auto& t : scene_types())
    if (t.name == name) return &t;
  return nullptr;
}

AreaLight core::make_area_light(const glm::vec3& center, const glm::vec3& target, float width,
                                float height, float intensity) {
  AreaLight l;
  l.center = center;
  l.target = target;
  l.intensity = intensity;
  const glm::vec3 dir = glm::normalize(target - center);
  // Any up vector not parallel to the direction spans the light's plane.
  const glm::vec3 up = std::fabs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(dir, up));
  const glm::vec3 v = glm::normalize(glm::cross(u, dir));
  l.half_u = 0.5f * width * u;
  l.half_v = 0.5f * height * v;
  return l;
}

AreaLight core::make_sun_light(const glm::vec3& to_sun, const glm::vec3& target,
                               float angular_diameter, float distance, float intensity) {
  const glm::vec3 center = target + glm::normalize(to_sun) * distance;
  const float diameter_there = 2.0f * distance * std::tan(0.5f * angular_diameter);
  AreaLight l = make_area_light(center, target, diameter_there, diameter_there, intensity);
  l.sun = true;
  l.angular_diameter = angular_diameter;
  return l;
}

}  // namespace sb
