// The bare template of `shadowbench new-technique --bare` (--family
// plugin_api): a shadow map from the light's centre with k×k percentage-closer filtering,
// written against the plugin API alone (core/, gl/, plugin/), with its own
// light frustum and depth pass; its config runs it beside shadow_map, pcf_box
// and pcss. It declares opaque_casters (its depth pass ignores alpha masks),
// so alpha-masked scenes skip it: not the default, which is the kit's
// (shadow_map.cpp). tests/out_of_tree/scaffold_build_and_run.py builds what it writes
// against an installed prefix and runs it.
#include <string>

#include "cli/technique_template.h"

namespace sb::cli {

TechniqueTemplate plugin_api_template() {
  TechniqueTemplate t;
  t.family = "plugin_api";
  t.summary = "a shadow map with k×k PCF on the plugin API alone";
  t.files.push_back(
      {"@NAME@.cpp", R"FILE(// @NAME@: a shadow map from the light's centre, filtered by k×k
// percentage-closer filtering (Reeves et al. 1987). Written by
// `shadowbench new-technique` against the plugin API alone; change it freely.
//
// The contract (shadowbench/plugin/technique.h): write V, the fraction of
// the area light each G-buffer point sees, into in.visibility_framebuffer.
//   prepare(): once per (scene, resolution), untimed: compile, allocate,
//              precompute what depends on the parameters only.
//   render():  every frame, timed: everything that depends on the light or
//              the camera (here the light's frustum), then the passes.
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <stdexcept>

#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace @NAME@_plugin {
namespace {

// Depth pass: caster depths seen from the light's centre.
constexpr const char* kDepthVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 light_view_projection;
void main() { gl_Position = light_view_projection * vec4(position, 1.0); }
)";

// Lookup pass: each G-buffer point, found in the map, k×k comparisons.
constexpr const char* kLookupFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2DShadow shadow_map;
layout(binding = 2) uniform sampler2D gbuffer_normal;
uniform mat4 light_view_projection;
uniform vec3 light_centre;
uniform int radius;  // (k - 1) / 2
out float visibility;
void main() {
  vec4 p = texelFetch(gbuffer_position, ivec2(gl_FragCoord.xy), 0);
  visibility = 1.0;
  if (p.w == 0.0) return;  // background: lit
  // Turned away from the light's centre: the surface shadows itself.
  vec3 n = texelFetch(gbuffer_normal, ivec2(gl_FragCoord.xy), 0).xyz;
  if (dot(n, light_centre - p.xyz) <= 0.0) {
    visibility = 0.0;
    return;
  }
  vec4 clip = light_view_projection * vec4(p.xyz, 1.0);
  if (clip.w <= 0.0) return;  // behind the light: every caster is in front
  vec3 t = 0.5 * clip.xyz / clip.w + 0.5;
  // Outside the map's cone: the cone holds every caster, so nothing occludes.
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return;
  // Beyond the far plane compares as the far plane: lit where no caster is.
  t.z = min(t.z, 1.0);
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  float lit = 0.0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x)
      lit += texture(shadow_map, vec3(t.xy + vec2(x, y) * texel, t.z));
  visibility = lit / float((2 * radius + 1) * (2 * radius + 1));
}
)";

class PcfShadowMap final : public sb::Technique {
 public:
  // Reads every declared parameter; no GL here (validate and plan create
  // techniques without a context).
  explicit PcfShadowMap(const sb::Params& p)
      : size_(p.get_int("size")),
        radius_((p.get_int("k") - 1) / 2),
        constant_bias_(p.get_float("constant_bias")),
        slope_bias_(p.get_float("slope_bias")) {}

  void prepare(const sb::FrameInputs& in) override {
    depth_program_ = sb::gl::Program("@NAME@ depth", {kDepthVertex, "", ""});
    lookup_program_ =
        sb::gl::Program("@NAME@ lookup", {sb::gl::kFullscreenVertexShader, "", kLookupFragment});
    lookup_program_.set("radius", radius_);
    map_ = sb::gl::make_depth_texture(GL_DEPTH_COMPONENT32F, size_, size_, /*compare=*/true);
    map_framebuffer_ = sb::gl::make_framebuffer({}, map_.get());
    // The casters' bounds are the scene's own, not the light's: fine here.
    casters_ = in.scene->caster_bounds();
  }

  void render(const sb::FrameInputs& in, sb::gl::PassTimer& timer) override {
    glm::mat4 light_view_projection{1.0f};
    {
      auto pass = timer.scope("shadow_map");
      // Fitted in every frame: it depends on the light (timed, like the
      // built-in shadow maps' fits).
      light_view_projection = fit_light(in.scene->light.center);
      glBindFramebuffer(GL_FRAMEBUFFER, map_framebuffer_.get());
      glViewport(0, 0, size_, size_);
      const float far_depth = 1.0f;
      glClearNamedFramebufferfv(map_framebuffer_.get(), GL_DEPTH, 0, &far_depth);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(slope_bias_, constant_bias_);
      depth_program_.use();
      depth_program_.set("light_view_projection", light_view_projection);
      in.gpu->draw_casters([](const sb::DrawInfo& mesh) {
        // A closed caster's faces turned away from the light make its map:
        // its lit side cannot shadow itself (Shypula 2008). An open one (a
        // roof quad) needs both faces. need::kCasterClosedness says which.
        if (mesh.cullable) {
          glEnable(GL_CULL_FACE);
          glCullFace(GL_FRONT);
        } else {
          glDisable(GL_CULL_FACE);
        }
      });
      glDisable(GL_CULL_FACE);
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
    auto pass = timer.scope("lookup");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    glDisable(GL_DEPTH_TEST);
    lookup_program_.use();
    lookup_program_.set("light_view_projection", light_view_projection);
    lookup_program_.set("light_centre", in.scene->light.center);
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(1, map_.get());
    glBindTextureUnit(2, in.gbuffer_normal);
    sb::gl::draw_fullscreen_triangle();
  }

 private:
  // A square perspective view from `eye` holding the casters' bounding
  // sphere, near and far planes on the sphere.
  glm::mat4 fit_light(const glm::vec3& eye) const {
    const glm::vec3 centre = casters_.center();
    const float r = casters_.radius();
    const float d = glm::length(centre - eye);
    if (!(d > 1.001f * r))
      throw std::runtime_error("@NAME@: the light's centre is inside the casters' bounds");
    const glm::vec3 axis = (centre - eye) / d;
    const glm::vec3 up =
        std::abs(axis.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::mat4 view = glm::lookAt(eye, centre, up);
    const glm::mat4 projection = glm::perspective(2.0f * std::asin(r / d), 1.0f, d - r, d + r);
    return projection * view;
  }

  int size_;
  int radius_;
  float constant_bias_, slope_bias_;
  sb::Bounds casters_;
  sb::gl::Program depth_program_, lookup_program_;
  sb::gl::Texture map_;
  sb::gl::Framebuffer map_framebuffer_;
};

}  // namespace
}  // namespace @NAME@_plugin

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add({
      .name = "@NAME@",    // the name configs use
      .family = "@NAME@",  // this plugin
      .summary = "shadow map with k×k percentage-closer filtering (plugin template)",
      // Which casters are closed (culled in the depth pass); and no
      // alpha-tested ones (leaves), which would need a masked depth pass.
      .needs = sb::Needs{sb::need::kCasterClosedness, sb::need::kOpaqueCasters},
      .params = {sb::int_param("size", 1024, 16, 8192, "shadow map size (texels a side)"),
                 sb::odd(sb::int_param("k", 3, 1, 15, "kernel side (odd): k*k depth comparisons")),
                 sb::float_param("constant_bias", 4.0, -1e6, 1e6,
                                 "glPolygonOffset units (depth pass)"),
                 sb::float_param("slope_bias", 2.0, -1e3, 1e3,
                                 "glPolygonOffset factor (depth pass)")},
      .create = [](const sb::Params& p) {
        return std::make_unique<@NAME@_plugin::PcfShadowMap>(p);
      }});
}
)FILE"});
  t.files.push_back(
      {"CMakeLists.txt",
       R"FILE(# The @NAME@ technique plugin, built against an installed shadowbench (or
# a build folder): find_package(shadowbench) gives the plugin API, and
# shadowbench_add_plugin makes @NAME@.so, which shadowbench loads from
# $SHADOWBENCH_PLUGIN_PATH.
cmake_minimum_required(VERSION 3.25)
project(@NAME@ LANGUAGES CXX)

find_package(shadowbench REQUIRED CONFIG)
shadowbench_add_plugin(@NAME@ @NAME@.cpp)
)FILE"});
  t.files.push_back({"@NAME@.json", R"FILE({
  "name": "@NAME@",
  "description": "@NAME@ beside its nearest built-ins, same map size, on a small sphere grid.",
  "scenes": [
    {"type": "sphere_grid", "params": {"grid": 3, "light_size": 2.0}}
  ],
  "techniques": [
    {"name": "shadow_map", "params": {"size": 1024}},
    {"name": "pcf_box", "params": {"k": 3, "size": 1024}},
    {"name": "pcss", "params": {"size": 1024}},
    {"name": "@NAME@", "params": {"k": 3, "size": 1024}}
  ],
  "resolutions": [[160, 120]],
  "frames": {"warmup": 1, "timed": 3},
  "reference": {"spp": 64, "seed": 1}
}
)FILE"});
  t.files.push_back(
      {"README.md",
       R"FILE(# @NAME@

A shadow technique plugin for shadowbench, written by
`shadowbench new-technique --bare`: a shadow map from the light's centre with
k×k percentage-closer filtering, using the plugin API alone. It declares
`opaque_casters` (its depth pass ignores alpha masks), so scenes with
alpha-masked casters (foliage) skip it; `shadowbench new-technique` without
`--bare` writes one on the shadow-map kit, which honours them. Edit `@NAME@.cpp`; `@NAME@.json` runs it beside
its nearest built-ins (shadow_map, pcf_box, pcss) on a small sphere grid.

)FILE" + std::string(kBuildLoadRun) +
           R"FILE(A rerun into the same folder resumes the jobs it finished, except those of a
plugin whose .so changed since: after a rebuild, @NAME@'s jobs run again
(records hold the plugin's SHA-256).

What a technique must do, and how to compare it fairly: the guide,
docs/writing_a_technique.md (installed under share/doc/shadowbench/).
)FILE"});
  return t;
}

}  // namespace sb::cli
