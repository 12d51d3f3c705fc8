#pragma once
// What the scene generators' tests share: a scene type built from JSON
// parameters as a config would build it, and a point in the scene camera's
// normalised device coordinates.
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "core/params.h"
#include "core/scene.h"
#include "core/scene_types.h"

namespace sb::test {

inline core::Scene build_scene_type(const std::string& type, const nlohmann::json& given) {
  const core::SceneType* t = core::find_scene_type(type);
  EXPECT_NE(t, nullptr) << type;
  return t->build(core::resolve_params(t->params, given, "test", "/params"));
}

// At the 4:3 aspect of the tests' framings.
inline glm::vec3 ndc_of(const core::Scene& s, glm::vec3 p) {
  const glm::vec4 clip = s.camera.projection(4.0f / 3.0f) * s.camera.view() * glm::vec4(p, 1.0f);
  EXPECT_GT(clip.w, 0.0f);
  return glm::vec3(clip) / clip.w;
}

}  // namespace sb::test
