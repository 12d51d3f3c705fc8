#include "two_map/penumbra_buffer.h"

#include <string>

#include "common/light_frame.h"
#include "common/silhouette_band.h"
#include "gl/debug.h"

namespace sb::techniques::two_map {

using core::AreaLight;
using plugin::FrameInputs;

const char* const kInnerImageGlsl = R"(
uniform mat4 apex_view;
uniform vec3 inner_apex;
uniform vec3 light_centre;
uniform vec3 light_axis;
vec2 apex_image(vec3 world) {
  vec3 e = (apex_view * vec4(world, 1.0)).xyz;
  return e.xy / -e.z;
}
vec2 inner_image(vec3 q, float zr) {
  float ze = dot(inner_apex - light_centre, light_axis), zq = dot(q - light_centre, light_axis);
  vec3 x = inner_apex + (q - inner_apex) * ((zr - ze) / (zq - ze));
  return apex_image(x);
}
)";

namespace {

const char* const kBandVertex = R"(
uniform vec3 apex;          // A, world
uniform mat4 apex_projection;
uniform vec2 apex_depth_range;  // A's near and far planes
uniform float far_axis;     // A's far plane as an axis depth from the light's centre
flat out vec2 a_image, b_image;
flat out vec3 p0, p1;
flat out vec2 view_depths;  // A's view depth of p0 and p1
flat out vec2 inward;
void main() {
  Edge e = edges[gl_VertexID / kBandVertices];
  if (!on_silhouette(e, apex)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  p0 = e.p0.xyz;
  p1 = e.p1.xyz;
  vec3 ea = (apex_view * vec4(p0, 1.0)).xyz, eb = (apex_view * vec4(p1, 1.0)).xyz;
  view_depths = vec2(-ea.z, -eb.z);
  a_image = ea.xy / -ea.z;
  b_image = eb.xy / -eb.z;
  vec3 m = 0.5 * (ea + eb), into = mat3(apex_view) * into_lit_face(e, apex);
  vec2 inside = into.xy + (m.xy / -m.z) * into.z;
  inward = -outward_normal(a_image, b_image, inside);
  // As far inside as E's shadow of either end reaches on the farthest receiver.
  float r = max(length(inner_image(p0, far_axis) - a_image), length(inner_image(p1, far_axis) - b_image));
  vec2 corner = band_corner(a_image, b_image, r, inward, gl_VertexID % kBandVertices);
  float z = 0.5 * (apex_depth_range.x + apex_depth_range.y);
  gl_Position = apex_projection * vec4(corner * z, -z, 1.0);
}
)";

const char* const kBandFragment = R"(
uniform float image_extent;   // the map's side in image units: depth = d / extent
flat in vec2 a_image, b_image;
flat in vec3 p0, p1;
flat in vec2 view_depths;
flat in vec2 inward;
out vec4 nearest;  // q, d
void main() {
  vec2 image = fragment_image();
  if (dot(image - a_image, inward) < 0.0) discard;  // the lit side
  float t = segment_param(image, a_image, b_image);
  // The edge's point at image parameter t (perspective: 1/z is linear in t).
  float u = t * view_depths.x / (t * view_depths.x + (1.0 - t) * view_depths.y);
  float d = length(image - mix(a_image, b_image, t));
  nearest = vec4(mix(p0, p1, u), d);
  gl_FragDepth = clamp(d / image_extent, 0.0, 1.0);  // the nearest edge wins
}
)";

}  // namespace

PenumbraBuffer::PenumbraBuffer(int size)
    : size_(size),
      texture_(gl::make_texture_2d(GL_RGBA32F, size, size)),
      depth_(gl::make_depth_texture(GL_DEPTH_COMPONENT32F, size, size, /*compare=*/false)),
      framebuffer_(gl::make_framebuffer({texture_.get()}, depth_.get())),
      program_(
          "two_map_bound_penumbra_buffer",
          {std::string("#version 450 core\n") + kSilhouetteBandVertexGlsl + kInnerImageGlsl +
               kBandVertex,
           "", std::string("#version 450 core\n") + kSilhouetteBandFragmentGlsl + kBandFragment}) {
  // Outside the map no band was drawn.
  glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float none[4] = {0.0f, 0.0f, 0.0f, -1.0f};
  glTextureParameterfv(texture_.get(), GL_TEXTURE_BORDER_COLOR, none);
  gl::throw_if_errors("two_map_bound penumbra buffer");
}

void PenumbraBuffer::render(const FrameInputs& in, const LightFrustum& frustum,
                            const glm::vec3& inner_apex) {
  const AreaLight& light = in.scene->light;
  const glm::vec3 axis = LightFrame(light).n;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, size_, size_);
  const float none[4] = {0.0f, 0.0f, 0.0f, -1.0f};
  const float far_depth = 1.0f;
  glClearBufferfv(GL_COLOR, 0, none);
  glClearBufferfv(GL_DEPTH, 0, &far_depth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  const gl::Program& p = program_;
  p.use();
  p.set_if_active("apex", frustum.eye);
  p.set_if_active("apex_view", frustum.view);
  p.set_if_active("apex_projection", frustum.projection);
  p.set_if_active("apex_depth_range", glm::vec2(frustum.near_plane, frustum.far_plane));
  p.set_if_active("far_axis", glm::dot(frustum.eye - light.center, axis) + frustum.far_plane);
  p.set_if_active("inner_apex", inner_apex);
  p.set_if_active("light_centre", light.center);
  p.set_if_active("light_axis", axis);
  set_fragment_image_uniforms(p, frustum, size_);
  p.set_if_active("image_extent", 2.0f * frustum.tan_half_fov);
  draw_silhouette_bands(in);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace sb::techniques::two_map
