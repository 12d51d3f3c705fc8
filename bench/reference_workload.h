#pragma once
// The reference benchmarks' workloads: a generated scene with its 800×600
// G-buffer made by primary ray casting (not timed). The default sphere grid
// is 81 UV spheres of 760 triangles over a ground plane.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/params.h"
#include "core/scene_types.h"
#include "reference/reference.h"

namespace sb::bench {

struct SceneWorkload {
  core::Scene scene;
  reference::GBuffer gbuffer;
  size_t covered = 0;  // pixels with a surface
};

// The scene type `type` at its defaults, with `overrides` on top.
inline SceneWorkload scene_workload(const std::string& type_name,
                                    const nlohmann::json& overrides = nlohmann::json::object()) {
  const core::SceneType* type = core::find_scene_type(type_name);
  if (!type) throw std::runtime_error("no " + type_name + " scene type");
  nlohmann::json params = nlohmann::json::object();
  for (const auto& p : type->params) params[p.name] = p.default_value;
  params.update(overrides);
  SceneWorkload out;
  out.scene = type->build(core::Params(params));
  out.gbuffer = reference::trace_gbuffer(out.scene, 800, 600);
  for (size_t i = 0; i < out.gbuffer.positions.pixel_count(); ++i)
    out.covered += out.gbuffer.positions.data[i * 4 + 3] > 0.5f;
  return out;
}

inline SceneWorkload default_sphere_grid() { return scene_workload("sphere_grid"); }

}  // namespace sb::bench
