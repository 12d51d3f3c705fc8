// The occlusion-texture family (Eisemann & Décoret 2008): one registration
// line per variant.
#include "occlusion_texture/occlusion_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::occlusion_texture::occlusion_textures_info());
}
