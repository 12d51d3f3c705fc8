#pragma once
// Scene generators known to the harness, each with its parameters as data.
// Every scene entry in a config may also override the light and the camera
// (see docs/config.md); those overrides are applied by the config layer.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"
#include "core/scene.h"

namespace sb::core {

struct SceneType {
  std::string name;
  std::string summary;
  std::vector<ParamSpec> params;
  std::function<Scene(const Params&)> build;
  // Optional rule across parameters, checked when a config or a scene spec is
  // loaded: returns "" when fine, else {parameter to blame, what is wrong}.
  std::function<std::pair<std::string, std::string>(const Params&)> check = nullptr;
};

const std::vector<SceneType>& scene_types();
const SceneType* find_scene_type(const std::string& name);
// Adds a scene type (tests, extensions); throws std::logic_error on a duplicate.
void add_scene_type(SceneType type);

// A rectangular light of size width×height at `center`, facing `target`.
AreaLight make_area_light(const glm::vec3& center, const glm::vec3& target, float width,
                          float height, float intensity = 1.0f);

// The sun seen from `target` towards `to_sun` (need not be unit), a disk of
// `angular_diameter` radians; its `center` at `distance` from target.
AreaLight make_sun_light(const glm::vec3& to_sun, const glm::vec3& target, float angular_diameter,
                         float distance, float intensity = 1.0f);

// The sun's angular diameter seen from the Earth, in degrees: the default
// for a sun light and for a glTF directional light.
inline constexpr float kSunDiameterDegrees = 0.53f;

}  // namespace sb::core
