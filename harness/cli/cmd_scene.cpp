// `shadowbench scene export` and `shadowbench scene info`.
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "core/error.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
#include "scenes/scene_spec.h"

namespace sb::cli {

using core::InputError;
using core::kExitOk;
using core::Scene;

int cmd_scene_export(const Args& a) {
  if (a.scene_spec.empty() || a.scene_out.empty())
    throw InputError("", "command line",
                     "expected 'scene export SCENE-SPEC OUT.glb' (see shadowbench scene export "
                     "--help)");
  const Scene s = build_scene_from_spec(a.scene_spec);
  export_glb(s, a.scene_out);
  std::printf("%s: %zu meshes, %zu triangles, %zu textures\n", a.scene_out.c_str(), s.meshes.size(),
              s.triangle_count(), s.textures.size());
  return kExitOk;
}

int cmd_scene_info(const Args& a) {
  if (a.scene_spec.empty())
    throw InputError("", "command line",
                     "expected 'scene info FILE|SCENE-SPEC' (see shadowbench scene info --help)");
  const std::string ext = std::filesystem::path(a.scene_spec).extension().string();
  const bool file = ext == ".glb" || ext == ".gltf" || ext == ".GLB" || ext == ".GLTF";
  std::printf(
      "%s",
      describe_scene(file ? load_gltf(a.scene_spec) : build_scene_from_spec(a.scene_spec)).c_str());
  return kExitOk;
}

}  // namespace sb::cli
