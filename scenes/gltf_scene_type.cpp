#include "scenes/gltf_scene_type.h"

#include "scenes/gltf_import.h"

namespace sb {

using core::float_param;
using core::Params;
using core::path_param;
using core::SceneType;

SceneType gltf_scene_type() {
  return {"gltf",
          "a glTF 2.0 file (.gltf/.glb): its default scene, first camera and first "
          "KHR_lights_punctual light (docs/scenes.md)",
          {path_param("file", "the .gltf or .glb file, relative to the config file"),
           float_param("light_size", 0.0, 0.0, 1e6,
                       "side of the square area light after scaling; 0: the size the file "
                       "stores (shadowbench export), else 5% of the scene's diagonal"),
           float_param("scale", 1.0, 1e-6, 1e6, "uniform scale of the whole scene")},
          [](const Params& p) {
            GltfImportOptions o;
            o.light_size = p.get_float("light_size");
            o.scale = p.get_float("scale");
            return load_gltf(p.get_string("file"), o);
          }};
}

}  // namespace sb
