#pragma once
#include "core/scene_types.h"

namespace sb {
// Geometry that breaks techniques (docs/stability.md): sliver triangles,
// degenerate triangles, coincident (z-fighting) casters and receivers, and
// occluders thinner than a shadow-map texel, each over a ground plane under a
// square area light. Parameters and placement are documented in
// stress_geometry.cpp.
core::SceneType stress_geometry_scene_type();
}  // namespace sb
