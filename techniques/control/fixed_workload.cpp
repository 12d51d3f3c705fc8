// fixed_workload — the control job of timing ratios (docs/ci.md, "Timings
// relative to a control"): a fixed amount of vertex, raster and texture work
// that stands for the machine's speed, with V = 1 everywhere.
//
// Why its own code: a control that shares code with the jobs it normalises
// hides a slowdown in that code (it divides out), and a control that is one
// of the gated jobs is compared with itself. So this file uses nothing from
// techniques/common, nor the scene: a heightfield grid generated from
// gl_VertexID is drawn into a depth map, then every pixel at the job's
// resolution reads a taps × taps block of it. Its cost is set by its
// parameters and the resolution alone.
#include <array>
#include <memory>
#include <string>

#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace sb::techniques::control {
namespace {

// grid × grid quads of a wavy heightfield over [-1, 1]², two triangles each,
// seen from above through a fixed orthographic projection.
constexpr const char* kGridVertexShader = R"(#version 450 core
uniform int grid;
void main() {
  const ivec2 corner[6] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1),
                                  ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
  int quad = gl_VertexID / 6;
  ivec2 cell = ivec2(quad % grid, quad / grid) + corner[gl_VertexID % 6];
  vec2 xy = vec2(cell) / float(grid) * 2.0 - 1.0;
  float height = 0.25 * sin(7.0 * xy.x) * cos(5.0 * xy.y) + 0.1 * sin(23.0 * (xy.x + xy.y));
  gl_Position = vec4(xy, height, 1.0);
}
)";

// Every pixel reads taps × taps texels of the depth map around its own
// place in it. The sum decides nothing that can be folded away (depths are
// never negative, but the compiler cannot know it), and V = 1.
constexpr const char* kReadFragmentShader = R"(#version 450 core
in vec2 uv;
out float visibility;
uniform sampler2D depth_map;
uniform int taps;
void main() {
  ivec2 size = textureSize(depth_map, 0);
  ivec2 centre = ivec2(uv * vec2(size));
  float sum = 0.0;
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i)
      sum += texelFetch(depth_map, clamp(centre + ivec2(i, j) - taps / 2, ivec2(0), size - 1), 0).r;
  visibility = sum >= 0.0 ? 1.0 : 0.5;
}
)";

class FixedWorkload final : public Technique {
 public:
  explicit FixedWorkload(const Params& p)
      : grid_(p.get_int("grid")), size_(p.get_int("size")), taps_(p.get_int("taps")) {}

  void prepare(const FrameInputs& /*in*/) override {
    grid_program_ = gl::Program("fixed_workload grid", {kGridVertexShader, "", ""});
    read_program_ =
        gl::Program("fixed_workload read", {gl::kFullscreenVertexShader, "", kReadFragmentShader});
    depth_ = gl::make_depth_texture(GL_DEPTH_COMPONENT32F, size_, size_, /*compare=*/false);
    depth_framebuffer_ = gl::make_framebuffer({}, depth_.get());
    grid_program_.set("grid", grid_);
    read_program_.set("taps", taps_);
    read_program_.set("depth_map", 0);
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    {
      auto pass = timer.scope("grid");
      glBindFramebuffer(GL_FRAMEBUFFER, depth_framebuffer_.get());
      glViewport(0, 0, size_, size_);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glClear(GL_DEPTH_BUFFER_BIT);
      grid_program_.use();
      glBindVertexArray(gl::empty_vertex_array());
      glDrawArrays(GL_TRIANGLES, 0, 6 * grid_ * grid_);
      glDisable(GL_DEPTH_TEST);
    }
    auto pass = timer.scope("read");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    read_program_.use();
    glBindTextureUnit(0, depth_.get());
    gl::draw_fullscreen_triangle();
  }

 private:
  int grid_, size_, taps_;
  gl::Program grid_program_, read_program_;
  gl::Texture depth_;
  gl::Framebuffer depth_framebuffer_;
};

}  // namespace
}  // namespace sb::techniques::control

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  using namespace sb::techniques::control;
  registry.add(
      {.name = "fixed_workload",
       .family = "control",
       .summary =
           "control for timing ratios: a fixed grid drawn into a depth map, read back per pixel; "
           "V = 1 (shares no code with any technique)",
       .needs = Needs{need::kSunOrLocalLight},
       .params = {int_param("grid", 128, 1, 2048,
                            "the heightfield's quads per side (2 grid² triangles)"),
                  int_param("size", 1024, 16, 8192, "the depth map's side in texels"),
                  int_param("taps", 3, 1, 15,
                            "grid SIDE, not a tap count: taps² texels read per pixel")},
       .create = [](const Params& p) { return std::make_unique<FixedWorkload>(p); }});
}
