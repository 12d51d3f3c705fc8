#pragma once
// A registered scene type built with the given parameters, the rest at their
// defaults: shared by the tests (one definition, so that a unity build of a
// test executable holds it once).
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/params.h"
#include "core/scene_types.h"

namespace sb::test {

inline core::Scene scene_of_type(const std::string& type_name,
                                 nlohmann::json params = nlohmann::json::object()) {
  const core::SceneType* type = core::find_scene_type(type_name);
  if (!type) throw std::runtime_error("no scene type " + type_name);
  for (const auto& p : type->params)
    if (!params.contains(p.name) && !p.default_value.is_null()) params[p.name] = p.default_value;
  return type->build(core::Params(params));
}

}  // namespace sb::test
