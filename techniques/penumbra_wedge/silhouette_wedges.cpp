#include "penumbra_wedge/silhouette_wedges.h"

namespace sb::techniques::penumbra_wedge {

using core::AreaLight;
using core::Bounds;
using core::Params;
using plugin::FrameInputs;

SilhouetteWedges::SilhouetteWedges(const Params& p)
    : volumes_(shadow_volume::count_mode_from_string(p.get_string("mode")), /*cpu=*/true,
               shadow_volume::silhouette_settings(p)) {}

void SilhouetteWedges::prepare(const FrameInputs& in) {
  volumes_.prepare(in);
  stream_.create();
}

void SilhouetteWedges::build(const FrameInputs& in, gl::PassTimer& timer) {
  const AreaLight& light = in.scene->light;
  {
    auto pass = timer.scope("silhouettes");
    volumes_.choose_zfail(in);
    volumes_.find_silhouettes(light.center);
  }
  {
    auto pass = timer.scope("volumes");
    volumes_.extrude(light.center);
  }
  {
    auto pass = timer.scope("wedges");
    frame_ = LightFrame(light);
    batch_.clear();
    caster_wedges_.assign(volumes_.silhouettes().size(), IndexRange{});
    const Bounds scene = in.scene->bounds();
    // No wedges when the whole scene is behind the light, or the light is a
    // point (no penumbra: V is the umbra's).
    if (frame_.has_area() && frame_.farthest(scene) > 0.0f) {
      const WedgeRange range = wedge_range(frame_, scene);
      for (size_t i = 0; i < caster_wedges_.size(); ++i)
        caster_wedges_[i] =
            append_silhouette_wedges(frame_, volumes_.silhouettes()[i], range, float(i), batch_);
    }
  }
  auto pass = timer.scope("upload");
  volumes_.upload();
  stream_.upload(batch_);  // orphaned and refilled every frame
}

void begin_hull_draw() {
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
}

void end_hull_draw() {
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
}

gl::Texture make_stencil_view(GLuint depth_stencil) {
  GLuint view = 0;
  glGenTextures(1, &view);
  glTextureView(view, GL_TEXTURE_2D, depth_stencil, GL_DEPTH24_STENCIL8, 0, 1, 0, 1);
  gl::Texture texture(view);
  glTextureParameteri(view, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
  glTextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return texture;
}

const char* const kStencilCountGlsl = R"(
float stencil_count(usampler2D stencil, ivec2 pixel) {
  uint count = texelFetch(stencil, pixel, 0).r;
  return float(count >= 128u ? int(count) - 256 : int(count));
}
)";

}  // namespace sb::techniques::penumbra_wedge
