// `shadowbench scene export` and `shadowbench scene info`.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
#include "scenes/scene_spec.h"

namespace sb::cli {

using core::InputError;
using core::kExitOk;
using core::Scene;

namespace {

struct SceneExportArgs {
  std::string scene_spec, scene_out;
};

struct SceneInfoArgs {
  std::string scene;  // a file or a SCENE-SPEC
};

int cmd_scene_export(const SceneExportArgs& a) {
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

int cmd_scene_info(const SceneInfoArgs& a) {
  if (a.scene.empty())
    throw InputError("", "command line",
                     "expected 'scene info FILE|SCENE-SPEC' (see shadowbench scene info --help)");
  const std::string ext = std::filesystem::path(a.scene).extension().string();
  const bool file = ext == ".glb" || ext == ".gltf" || ext == ".GLB" || ext == ".GLTF";
  std::printf("%s",
              describe_scene(file ? load_gltf(a.scene) : build_scene_from_spec(a.scene)).c_str());
  return kExitOk;
}

}  // namespace

void add_scene_commands(CommandLine& cl) {
  CLI::App* scene =
      cl.add_command(cl.app(), "scene", "Export a generated scene, or describe a scene.",
                     "shadowbench scene info configs/models/jeep.glb");
  scene->require_subcommand(1);
  const auto exported = std::make_shared<SceneExportArgs>();
  CLI::App* scene_export =
      cl.add_command(*scene, "export", "Write a generated scene as a binary glTF file.",
                     "shadowbench scene export sphere_grid:grid=3,light_size=2 grid.glb",
                     [exported] { return cmd_scene_export(*exported); });
  add_argument(scene_export, "SCENE-SPEC", exported->scene_spec,
               "TYPE:key=value,... or a JSON object {\"type\": ..., \"params\": {...}}");
  add_argument(scene_export, "OUT", exported->scene_out, "the .glb file to write");
  const auto described = std::make_shared<SceneInfoArgs>();
  CLI::App* scene_info = cl.add_command(
      *scene, "info", "Describe a scene: meshes, triangles, materials, light, bounds.",
      "shadowbench scene info configs/models/jeep.glb",
      [described] { return cmd_scene_info(*described); });
  add_argument(scene_info, "SCENE", described->scene, "a .glb or .gltf file, or a SCENE-SPEC");
}

}  // namespace sb::cli
