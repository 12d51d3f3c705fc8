#pragma once
#include "core/scene_types.h"

namespace sb {
// Procedural trees: closed tapered-cylinder trunks and branches, and
// alpha-tested, double-sided leaf quads carrying a generated leaf mask. Almost
// every leaf edge is a silhouette and the leaves are thin, open occluders.
core::SceneType foliage_scene_type();
}  // namespace sb
