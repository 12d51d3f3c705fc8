// virtual_shadow_map — a virtual (paged) shadow map for the sun, in the
// style of Unreal Engine 5's virtual shadow maps (after Fernando et al. 2001,
// adaptive shadow maps, and Lefohn et al. 2007, resolution-matched shadow
// maps): a clipmap of `levels` orthographic levels from the sun, each
// virtual_size² texels and twice the extent of the one before, centred on
// the camera, split into pages of page_size²; only the pages the view needs
// are rendered, into a physical pool of size² texels.
//
// Every frame (render(), timed): "page_marking" (the clipmap's levels; a
// compute pass over the G-buffer positions marks, per pixel, the pages its
// lookup will read; the marks read back), "allocation" (slots in the pool,
// on the CPU, with the overflow rule; the page table uploaded),
// "shadow_map" (the casters drawn once per run of pages consecutive in a
// level's row and in the pool), "lookup" (virtual texel → page table →
// physical texel).
//
// Parameters, defaults and ranges: docs/parameters.md; the technique, its
// rules and the papers: docs/sun.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cascaded/cascade_fit.h"
#include "cascaded/cascaded_variants.h"
#include "cascaded/virtual_pages.h"
#include "cascaded/virtual_shadow_map_glsl.h"
#include "common/depth_pass.h"
#include "common/glsl_pcf.h"
#include "core/error.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"

namespace sb::techniques::cascaded {
namespace {

using core::choice_param;
using core::int_param;
using core::odd;
using core::Params;
using core::ParamSpec;
using plugin::FrameInputs;
using plugin::TechniqueInfo;

constexpr int kMaxLevels = 24;
// The page table and the mark buffer hold 4 bytes per page of every level:
// at most 16 MiB each (the defaults: 1 MiB).
constexpr std::int64_t kMaxPages = std::int64_t(1) << 22;

const char* const kMaskedPageFragment = R"(#version 450 core
in vec2 v_uv;
layout(binding = 0) uniform sampler2D base_color;
uniform float alpha_cutoff;
void main() {
  if (texture(base_color, v_uv).a < alpha_cutoff) discard;
}
)";

int output_mode(const std::string& s) {
  return s == "level" ? 1 : s == "slot" ? 2 : s == "fallback" ? 3 : s == "page_table" ? 4 : 0;
}

class VirtualShadowMap final : public plugin::Technique {
 public:
  explicit VirtualShadowMap(const Params& p)
      : settings_(depth_map_settings(p)),
        virtual_size_(p.get_int("virtual_size")),
        page_size_(p.get_int("page_size")),
        levels_(p.get_int("levels")),
        filter_(p.get_string("filter") == "hard" ? 0 : 1),
        filter_radius_(p.get_int("filter_taps") / 2),
        output_(output_mode(p.get_string("output"))) {
    pages_per_side_ = std::max(virtual_size_ / page_size_, 1);
    pool_pages_side_ = std::max(settings_.size / page_size_, 1);
    // Texels the lookup reads around the pixel's own: the PCF grid's reach
    // and its bilinear taps' second texel, and the normal offset.
    margin_ = (filter_ == 1 ? filter_radius_ + 1 : 0) + int(std::ceil(settings_.normal_offset));
  }

  void prepare(const FrameInputs& in) override {
    const size_t pages = size_t(levels_) * size_t(pages_per_side_) * size_t(pages_per_side_);
    if (std::int64_t(pages) > kMaxPages)
      throw core::JobError("virtual_shadow_map: levels × (virtual_size / page_size)² = " +
                           std::to_string(pages) + " pages, over the " + std::to_string(kMaxPages) +
                           " its page table holds: fewer levels, a smaller virtual_size or a "
                           "larger page_size");
    // Fixed scene data: the casters' and the scene's bounding boxes.
    const core::Bounds casters = in.scene->caster_bounds(), scene = in.scene->bounds();
    caster_corners_ = box_corners(casters.lo, casters.hi);
    scene_corners_ = box_corners(scene.lo, scene.hi);
    const int pool_texels = pool_pages_side_ * page_size_;
    pool_ = gl::make_depth_texture(settings_.depth_format, pool_texels, pool_texels, false);
    pool_framebuffer_ = gl::make_framebuffer({}, pool_.get());
    page_table_ = gl::make_texture_2d_array(GL_R32I, pages_per_side_, pages_per_side_, levels_);
    marks_ =
        gl::make_buffer(GLsizeiptr(pages * sizeof(std::uint32_t)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    mark_values_.resize(pages);
    mark_program_ =
        gl::Program::compute("virtual_shadow_map_mark", std::string("#version 450 core\n") +
                                                            kVirtualClipmapGlsl + kVirtualMarkGlsl);
    lookup_ = gl::Program("virtual_shadow_map_lookup",
                          {gl::kFullscreenVertexShader, "",
                           std::string("#version 450 core\n") + kVirtualClipmapGlsl +
                               kVirtualLookupInputsGlsl + kPcfGlsl + kVirtualLookupGlsl});
    depth_program_ = gl::Program("virtual_shadow_map_depth", {gl::kSceneVertexShader, "", ""});
    masked_program_ = gl::Program("virtual_shadow_map_depth_masked",
                                  {gl::kSceneVertexShader, "", kMaskedPageFragment});
    for (const gl::Program* p : {&mark_program_, &lookup_}) {
      p->set_if_active("virtual_size", pages_per_side_ * page_size_);
      p->set_if_active("page_size", page_size_);
      p->set_if_active("pages_per_side", pages_per_side_);
      p->set_if_active("level_count", levels_);
      p->set_if_active("margin", margin_);
    }
    mark_program_.set("image_size", glm::ivec2(in.width, in.height));
    lookup_.set_if_active("pool_pages_side", pool_pages_side_);
    lookup_.set_if_active("normal_offset", settings_.normal_offset);
    lookup_.set_if_active("filter_mode", filter_);
    lookup_.set_if_active("filter_radius", filter_radius_);
    lookup_.set("output_mode", output_);
    gl::throw_if_errors("virtual_shadow_map prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const core::AreaLight& light = in.scene->light;
    Clipmap clip;
    {
      auto pass = timer.scope("page_marking");
      clip = view_clipmap(in.view, in.projection, in.height, light.direction(), caster_corners_,
                          scene_corners_, virtual_size_, page_size_, levels_);
      set_clipmap_uniforms(mark_program_, clip);
      glClearNamedBufferData(marks_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &kUnmarked);
      mark_program_.use();
      glBindTextureUnit(0, in.gbuffer_position);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, marks_.get());
      glDispatchCompute(GLuint((in.width + 7) / 8), GLuint((in.height + 7) / 8), 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(marks_.get(), 0,
                              GLsizeiptr(mark_values_.size() * sizeof(std::uint32_t)),
                              mark_values_.data());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    }
    PageAllocation alloc;
    {
      auto pass = timer.scope("allocation");
      alloc = allocate_pages(mark_values_, levels_, pages_per_side_, pool_pages_side_);
      glTextureSubImage3D(page_table_.get(), 0, 0, 0, 0, pages_per_side_, pages_per_side_, levels_,
                          GL_RED_INTEGER, GL_INT, alloc.table.data());
    }
    {
      auto pass = timer.scope("shadow_map");
      render_pages(in, clip, alloc);
    }
    auto pass = timer.scope("lookup");
    set_clipmap_uniforms(lookup_, clip);
    lookup_.set_if_active("to_sun", light.to_sun());
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    glDisable(GL_DEPTH_TEST);
    lookup_.use();
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(2, in.gbuffer_normal);
    glBindTextureUnit(4, pool_.get());
    glBindTextureUnit(5, page_table_.get());
    gl::draw_fullscreen_triangle();
  }

 private:
  void set_clipmap_uniforms(const gl::Program& p, const Clipmap& clip) const {
    std::array<glm::vec3, kMaxLevels> lo_texel{};
    for (int l = 0; l < levels_; ++l)
      lo_texel[size_t(l)] = {clip.levels[size_t(l)].lo, clip.levels[size_t(l)].texel};
    if (p.has_uniform("level_lo_texel"))
      glProgramUniform3fv(p.id(), p.location("level_lo_texel"), levels_, &lo_texel[0][0]);
    p.set_if_active("light_view", clip.view);
    p.set_if_active("near_depth", clip.near_depth);
    p.set_if_active("far_depth", clip.far_depth);
    p.set_if_active("eye", clip.eye);
    p.set_if_active("pixel_angle", clip.pixel_angle);
  }

  // Each run of pages: its rectangle of the pool cleared, then the casters
  // drawn with the run's orthographic sub-frustum.
  void render_pages(const FrameInputs& in, const Clipmap& clip, const PageAllocation& alloc) {
    glBindFramebuffer(GL_FRAMEBUFFER, pool_framebuffer_.get());
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    if (settings_.bias.constant != 0.0f || settings_.bias.slope != 0.0f) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(settings_.bias.slope, settings_.bias.constant);
    }
    for (const PageRun& run : alloc.runs) {
      const int x = (run.slot0 % pool_pages_side_) * page_size_;
      const int y = (run.slot0 / pool_pages_side_) * page_size_;
      glViewport(x, y, run.count * page_size_, page_size_);
      glScissor(x, y, run.count * page_size_, page_size_);
      glClear(GL_DEPTH_BUFFER_BIT);
      const glm::mat4 vp = clip.pages_view_projection(run.level, run.row, run.col0, run.count);
      depth_program_.set("view_projection", vp);
      masked_program_.set("view_projection", vp);
      const gl::Program* current = nullptr;
      in.gpu->draw_casters([&](const gl::DrawInfo& d) {
        const gl::Program* wanted = d.alpha_tested ? &masked_program_ : &depth_program_;
        if (wanted != current) {
          wanted->use();
          current = wanted;
        }
        if (d.alpha_tested) {
          masked_program_.set("alpha_cutoff", d.alpha_cutoff);
          glBindTextureUnit(0, d.texture);
        }
        set_depth_pass_cull(settings_.cull, d);
      });
    }
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_CULL_FACE);
  }

  DepthMapSettings settings_;
  int virtual_size_;
  int page_size_;
  int levels_;
  int filter_;
  int filter_radius_;
  int output_;
  int pages_per_side_ = 1;
  int pool_pages_side_ = 1;
  int margin_ = 0;
  std::array<glm::vec3, 8> caster_corners_{};
  std::array<glm::vec3, 8> scene_corners_{};
  std::vector<std::uint32_t> mark_values_;
  gl::Texture pool_;
  gl::Framebuffer pool_framebuffer_;
  gl::Texture page_table_;
  gl::Buffer marks_;
  gl::Program mark_program_;
  gl::Program lookup_;
  gl::Program depth_program_;
  gl::Program masked_program_;
};

}  // namespace

TechniqueInfo virtual_shadow_map_info() {
  std::vector<ParamSpec> params = {
      int_param("virtual_size", 16384, 256, 65536,
                "each clipmap level's virtual side in texels (rounded down to whole pages)"),
      int_param("page_size", 128, 16, 1024, "a page's side in texels"),
      int_param("levels", 16, 1, kMaxLevels,
                "clipmap levels, each twice the extent of the one before; the coarsest covers "
                "the view and its texels the farthest pixel's footprint"),
      choice_param("filter", "pcf", {"hard", "pcf"},
                   "one comparison, or a PCF grid of bilinear comparisons read texel by texel "
                   "through the page table (across page borders)"),
      odd(int_param("filter_taps", 3, 1, 31,
                    "PCF grid SIDE (odd), not a tap count: side² bilinear taps one texel apart")),
      choice_param("output", "visibility",
                   {"visibility", "level", "slot", "fallback", "page_table"},
                   "not a shadow but for looking: level (0 finest .. 1 coarsest), slot (the "
                   "pixel's page's pool slot + 1 over the pool's pages, 0 none), fallback (0 own "
                   "level, 0.5 the coarsest, 1 no page: lit), page_table (the table row-major "
                   "over the image: 1 allocated, 0.5 dropped, 0 unmarked)")};
  for (auto& p : depth_map_params(4096)) {
    if (p.name == "size") p.doc = "the physical pool's side in texels: (size / page_size)² pages";
    if (p.name == "normal_offset") p.doc += " (texels of the pixel's level)";
    params.push_back(std::move(p));
  }
  return {.name = "virtual_shadow_map",
          .family = "cascaded",
          .summary =
              "virtual (paged) shadow map for the sun: clipmap levels centred on the camera, "
              "pages marked from the G-buffer each frame and drawn into a physical pool",
          .needs = Needs{need::kSunLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<VirtualShadowMap>(p); }};
}

}  // namespace sb::techniques::cascaded
