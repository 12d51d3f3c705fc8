#pragma once
// The reference benchmarks' workload: the default sphere grid (81 UV spheres
// of 760 triangles over a ground plane) and its 800×600 G-buffer made by
// primary ray casting.
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/params.h"
#include "core/scene_types.h"
#include "reference/reference.h"

namespace sb::bench {

struct SphereGrid {
  Scene scene;
  reference::GBuffer gbuffer;
  size_t covered = 0;  // pixels with a surface
};

inline SphereGrid default_sphere_grid() {
  const SceneType* type = find_scene_type("sphere_grid");
  if (!type) throw std::runtime_error("no sphere_grid scene type");
  nlohmann::json defaults = nlohmann::json::object();
  for (const auto& p : type->params) defaults[p.name] = p.default_value;
  SphereGrid out;
  out.scene = type->build(Params(defaults));
  out.gbuffer = reference::trace_gbuffer(out.scene, 800, 600);
  for (size_t i = 0; i < out.gbuffer.positions.pixel_count(); ++i)
    out.covered += out.gbuffer.positions.data[i * 4 + 3] > 0.5f;
  return out;
}

}  // namespace sb::bench
