// virtual_shadow_map rendered on a small sun scene built here (boxes over a
// ground, the camera low over it, a sun of tiny angular size), through the
// harness's own stage (run/timing_contract.h): its page marking against the
// pages the G-buffer's pixels project into, computed here on the CPU; hard
// V against the analytic shadow (a ground point is shadowed exactly when
// its ray towards the sun hits a box) near the camera, where a single
// pool-sized map is too coarse; PCF kernels across page borders; the
// overflow rule on a pool too small; the timing contract under a turning
// sun; its GPU memory (drives Mesa).
//
// With SB_VSM_IMAGES=<folder> set, the tests write what they render there
// (V as PGM, the pool slot of each pixel's page in colours as PPM).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "cascaded/cascade_fit.h"
#include "cascaded/virtual_pages.h"
#include "core/scene_types.h"
#include "gl/allocation_meter.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::Params;
using core::resolve_params;
using core::Scene;
using plugin::Registry;
using plugin::TechniqueInfo;
using run::ContractStage;
using techniques::cascaded::box_corners;
using techniques::cascaded::Clipmap;
using techniques::cascaded::level_texel;
using techniques::cascaded::pixel_level;
using techniques::cascaded::view_clipmap;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

struct Box {
  glm::vec3 center, half;
};
const Box kBoxes[] = {{{-0.6f, 0.3f, 1.0f}, {0.25f, 0.3f, 0.25f}},
                      {{0.8f, 0.5f, -1.5f}, {0.3f, 0.5f, 0.3f}},
                      {{-1.5f, 1.0f, -6.0f}, {0.8f, 1.0f, 0.8f}},
                      {{2.5f, 1.5f, -15.0f}, {1.2f, 1.5f, 1.2f}}};
const glm::vec3 kToSun = glm::normalize(glm::vec3(0.9f, 0.8f, 0.3f));

Scene sun_scene() {
  Scene s;
  s.name = "virtual_boxes";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -10.0f}, 300.0f));
  for (size_t i = 0; i < std::size(kBoxes); ++i)
    s.meshes.push_back(make_box("box" + std::to_string(i), kBoxes[i].center, kBoxes[i].half));
  s.light = core::make_sun_light(kToSun, {0.0f, 0.0f, -10.0f}, 1e-4f, 80.0f);
  s.camera.eye = {0.0f, 1.6f, 4.0f};
  s.camera.target = {0.0f, 0.0f, -6.0f};
  s.camera.fov_y_degrees = 55.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 200.0f;
  return s;
}

// Does the ray from p towards the sun hit a box (slab test)?
bool shadowed(const glm::vec3& p) {
  for (const Box& b : kBoxes) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int k = 0; k < 3; ++k) {
      const float lo = (b.center[k] - b.half[k] - p[k]) / kToSun[k];
      const float hi = (b.center[k] + b.half[k] - p[k]) / kToSun[k];
      t0 = std::max(t0, std::min(lo, hi));
      t1 = std::min(t1, std::max(lo, hi));
    }
    if (t0 <= t1) return true;
  }
  return false;
}

// The analytic answer where all ground points within `margin` agree (away
// from the shadow's edge); -1 elsewhere.
float analytic_away_from_edges(const glm::vec3& p, float margin) {
  const bool centre = shadowed(p);
  for (int k = 0; k < 16; ++k) {
    const float a = float(k) * 0.392699f;
    if (shadowed(p + margin * glm::vec3(std::cos(a), 0.0f, std::sin(a))) != centre) return -1.0f;
  }
  return centre ? 0.0f : 1.0f;
}

void maybe_write(const ImageF& img, const std::string& name, bool colours = false) {
  const char* dir = std::getenv("SB_VSM_IMAGES");
  if (!dir) return;
  std::ofstream f(std::string(dir) + "/" + name + (colours ? ".ppm" : ".pgm"), std::ios::binary);
  f << (colours ? "P6\n" : "P5\n") << img.width << " " << img.height << "\n255\n";
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float v = img.at(x, y);
      if (!colours) {
        f.put(char(std::clamp(int(std::lround(255.0f * v)), 0, 255)));
        continue;
      }
      // A colour per value (0: black), hashed so that neighbours differ.
      std::uint32_t h = std::uint32_t(v * 1e6f) * 2654435761u;
      for (int c = 0; c < 3; ++c) f.put(v == 0.0f ? char(0) : char(64 + ((h >> (8 * c)) & 191)));
    }
}

class VirtualShadowMapRender : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    info_ = plugins_.find("virtual_shadow_map");
    ASSERT_NE(info_, nullptr);
    stage_ =
        std::make_unique<ContractStage>(sun_scene(), kWidth, kHeight, std::vector{info_}, plugins_);
    ASSERT_EQ(stage_->skip_reason(0), "");
  }
  ImageF render(const TechniqueInfo& info, const nlohmann::json& p) {
    const auto t = info.create(resolve_params(info.params, p, "", ""));
    t->prepare(stage_->inputs());
    return stage_->render(*t);
  }
  ImageF render(const nlohmann::json& p) { return render(*info_, p); }
  Clipmap clipmap(int virtual_size, int page_size, int levels) {
    const Scene& s = stage_->scene();
    const core::Bounds c = s.caster_bounds(), b = s.bounds();
    return view_clipmap(stage_->inputs().view, stage_->inputs().projection, kHeight,
                        s.light.direction(), box_corners(c.lo, c.hi), box_corners(b.lo, b.hi),
                        virtual_size, page_size, levels);
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  const TechniqueInfo* info_ = nullptr;
  std::unique_ptr<ContractStage> stage_;
};

TEST_F(VirtualShadowMapRender, IsSkippedUnderALocalLight) {
  ContractStage local(run::contract_scene(), 64, 48, std::vector{info_}, plugins_);
  EXPECT_NE(local.skip_reason(0), "");
}

// The pages the G-buffer's pixels project into, on the CPU: for each
// covered pixel, its level's page and the coarsest level's (hard lookups,
// no normal offset: no margin). `sure` holds the pages of pixels clear of
// any rounding question; `maybe` those of pixels within 0.01 texel of a
// page's side or 1e-4 of a level change in log2 footprint, where the GPU's
// float arithmetic may round the other way (with their neighbours). Per
// page, also its nearest pixel's distance.
struct CpuMarks {
  std::set<int> sure, maybe;
  std::map<int, float> distance;
};
CpuMarks cpu_marks(const ImageF& position, const Clipmap& c) {
  CpuMarks m;
  const int levels = int(c.levels.size()), side = c.pages_per_side;
  const auto page_index = [&](int l, glm::vec2 t) {
    const glm::ivec2 p = glm::clamp(glm::ivec2(glm::floor(t / float(c.page_size))), glm::ivec2(0),
                                    glm::ivec2(side - 1));
    return (l * side + p.y) * side + p.x;
  };
  for (int y = 0; y < position.height; ++y)
    for (int x = 0; x < position.width; ++x) {
      if (position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      const int l = pixel_level(c, p, 0);
      const float ratio = std::log2(glm::distance(p, c.eye) * c.pixel_angle / c.levels[0].texel);
      bool ambiguous = std::abs(ratio - std::round(ratio)) < 1e-4f;
      for (int k : {l, levels - 1}) {
        const glm::vec2 t = level_texel(c, k, p);
        const glm::vec2 f = t / float(c.page_size) - glm::floor(t / float(c.page_size));
        ambiguous = ambiguous ||
                    glm::any(glm::lessThan(f * float(c.page_size), glm::vec2(0.01f))) ||
                    glm::any(glm::greaterThan(f * float(c.page_size),
                                              glm::vec2(float(c.page_size) - 0.01f)));
      }
      const float d = glm::distance(p, c.eye);
      for (int k : {l, levels - 1}) {
        const int i = page_index(k, level_texel(c, k, p));
        m.distance[i] = m.distance.count(i) ? std::min(m.distance[i], d) : d;
        if (!ambiguous) m.sure.insert(i);
      }
      if (ambiguous)
        for (int k = std::max(l - 1, 0); k <= std::min(l + 1, levels - 1); ++k)
          for (int kk : {k, levels - 1})
            for (float dx : {-0.02f, 0.0f, 0.02f})
              for (float dy : {-0.02f, 0.0f, 0.02f})
                m.maybe.insert(page_index(kk, level_texel(c, kk, p) + glm::vec2(dx, dy)));
    }
  return m;
}

// The page table the technique's output "page_table" lays over the image:
// entry i at pixel i, row-major from the bottom row (GL's; the read-back
// image's rows run from the top).
std::map<int, float> gpu_table(const ImageF& v, int entries) {
  std::map<int, float> out;
  for (int i = 0; i < entries; ++i) {
    const float e = v.at(i % v.width, v.height - 1 - i / v.width);
    if (e != 0.0f) out[i] = e;
  }
  return out;
}

const nlohmann::json kSmall = {{"virtual_size", 2048},
                               {"page_size", 64},
                               {"levels", 8},
                               {"filter", "hard"},
                               {"normal_offset", 0.0}};

// Page marking: the pages the technique marked (and allocated: its pool
// holds them all) are the pages the pixels project into, no more, no fewer.
TEST_F(VirtualShadowMapRender, MarksExactlyThePagesTheGBufferPixelsProjectInto) {
  nlohmann::json p = kSmall;
  p["size"] = 4096;  // 64² slots: no overflow
  p["output"] = "page_table";
  const ImageF table_image = render(p);
  const Clipmap c = clipmap(2048, 64, 8);
  const int entries = 8 * 32 * 32;
  const std::map<int, float> gpu = gpu_table(table_image, entries);
  const CpuMarks cpu = cpu_marks(stage_->read_gbuffer()[0], c);
  ASSERT_GT(cpu.sure.size(), 20u);
  std::set<int> levels_used;
  for (int i : cpu.sure) levels_used.insert(i / (32 * 32));
  EXPECT_GE(levels_used.size(), 3u) << "the view should span several levels";
  for (int i : cpu.sure) EXPECT_EQ(gpu.count(i), 1u) << "page " << i << " not marked";
  for (const auto& [i, e] : gpu) {
    EXPECT_EQ(e, 1.0f) << "page " << i << " dropped though the pool holds every page";
    EXPECT_TRUE(cpu.sure.count(i) || cpu.maybe.count(i)) << "page " << i << " marked needlessly";
  }
  std::printf("marked %zu pages (CPU: %zu sure, %zu within rounding) over %zu levels\n", gpu.size(),
              cpu.sure.size(), cpu.maybe.size(), levels_used.size());
}

// Counts, over ground pixels nearer than 6 units to the eye and clear of
// the shadow's edge by 2 pixel footprints (at least 1 cm), those whose V
// differs from the analytic shadow.
struct Mismatch {
  int compared = 0, in_shadow = 0, wrong = 0;
};
Mismatch near_mismatch(const ImageF& v, const ImageF& position, const Clipmap& c) {
  Mismatch m;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      const float d = glm::distance(p, c.eye);
      if (std::abs(p.y) > 1e-3f || d > 6.0f) continue;
      const float expected = analytic_away_from_edges(p, std::max(2.0f * d * c.pixel_angle, 0.01f));
      if (expected < 0.0f) continue;
      ++m.compared;
      m.in_shadow += expected == 0.0f;
      m.wrong += std::abs(v.at(x, y) - expected) > 0.5f;
    }
  return m;
}

// Near the camera the pixels' footprints are a few millimetres: the
// virtual map's levels match them (a 16384² level of 2 cm texels or finer
// there), where one map of the pool's size (2048², fitted to the whole
// view: cascaded_shadow_map with one cascade) has texels of about 6 cm.
// The virtual map matches the analytic shadow 2 footprints from its edge;
// the single map misses there many times as often.
TEST_F(VirtualShadowMapRender, HardShadowsNearTheCameraMatchTheBoxesWhereAPoolSizedMapCannot) {
  const ImageF v = render({{"filter", "hard"}, {"size", 2048}});
  const ImageF slot = render({{"filter", "hard"}, {"size", 2048}, {"output", "slot"}});
  const ImageF level = render({{"filter", "hard"}, {"size", 2048}, {"output", "level"}});
  const TechniqueInfo* csm = plugins_.find("cascaded_shadow_map");
  ASSERT_NE(csm, nullptr);
  const ImageF single =
      render(*csm, {{"filter", "hard"}, {"size", 2048}, {"cascades", 1}, {"stable", false}});
  maybe_write(v, "boxes_v");
  maybe_write(slot, "boxes_slot", true);
  maybe_write(level, "boxes_level");
  maybe_write(single, "boxes_single_map_v");
  const ImageF position = stage_->read_gbuffer()[0];
  const Clipmap c = clipmap(16384, 128, 16);
  const Mismatch vsm = near_mismatch(v, position, c), one = near_mismatch(single, position, c);
  std::printf("near pixels: virtual %d wrong of %d (%d shadowed), single map %d wrong\n", vsm.wrong,
              vsm.compared, vsm.in_shadow, one.wrong);
  ASSERT_GT(vsm.compared, 5000);
  ASSERT_GT(vsm.in_shadow, 500);
  EXPECT_LE(vsm.wrong, vsm.compared / 500);
  EXPECT_GT(one.wrong, 10 * std::max(vsm.wrong, 5)) << "the single map is not coarser here";
}

// PCF reads each texel through the page table, so a kernel that crosses a
// page border reads the neighbouring page, which the marking marked for it
// (its reach: 1 texel of grid, 1 of bilinear taps): no pixel falls back,
// and V matches the analytic shadow 2 footprints (at least 2 texels) from
// its edge, on pixels whose kernel straddles a page border too.
TEST_F(VirtualShadowMapRender, PcfKernelsCrossPageBordersThroughThePageTable) {
  const nlohmann::json p = {{"filter", "pcf"}, {"filter_taps", 3}, {"size", 2048}};
  const ImageF v = render(p);
  nlohmann::json f = p;
  f["output"] = "fallback";
  const ImageF fallback = render(f);
  const ImageF position = stage_->read_gbuffer()[0];
  const Clipmap c = clipmap(16384, 128, 16);
  int compared = 0, wrong = 0, straddling = 0, fell_back = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (position.at(x, y, 3) == 0.0f) continue;
      fell_back += fallback.at(x, y) != 0.0f;
      const glm::vec3 q{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      const float d = glm::distance(q, c.eye);
      if (std::abs(q.y) > 1e-3f || d > 6.0f) continue;
      const float expected = analytic_away_from_edges(q, std::max(2.0f * d * c.pixel_angle, 0.01f));
      if (expected < 0.0f) continue;
      const glm::vec2 t = level_texel(c, pixel_level(c, q, 2), q);
      const glm::ivec2 lo = glm::ivec2(glm::floor((t - 1.5f) / 128.0f)),
                       hi = glm::ivec2(glm::floor((t + 1.5f) / 128.0f));
      straddling += lo != hi;
      ++compared;
      wrong += std::abs(v.at(x, y) - expected) > 0.5f;
    }
  std::printf("pcf: %d wrong of %d near pixels, %d straddle a page border\n", wrong, compared,
              straddling);
  EXPECT_EQ(fell_back, 0);
  EXPECT_GT(straddling, 100);
  EXPECT_LE(wrong, compared / 500);
}

// Overflow: a pool of 4×4 pages for more marked pages. The rule: the
// coarsest level's pages first, then the nearest (by their nearest
// pixel's distance); the rest dropped (0.5 in the page table), and their
// pixels fall back to the coarsest level.
TEST_F(VirtualShadowMapRender, AnOverflowingPoolKeepsTheCoarsestThenTheNearestPages) {
  nlohmann::json p = kSmall;
  p["size"] = 256;  // 16 slots
  p["output"] = "page_table";
  const ImageF table_image = render(p);
  p["output"] = "fallback";
  const ImageF fallback = render(p);
  p["output"] = "visibility";
  const ImageF v = render(p);
  maybe_write(fallback, "overflow_fallback");
  maybe_write(v, "overflow_v");
  const Clipmap c = clipmap(2048, 64, 8);
  const std::map<int, float> gpu = gpu_table(table_image, 8 * 32 * 32);
  const CpuMarks cpu = cpu_marks(stage_->read_gbuffer()[0], c);
  int allocated = 0, dropped = 0;
  float farthest_kept = 0.0f, nearest_dropped = 1e30f;
  const int coarsest_start = 7 * 32 * 32;
  int coarsest = 0;
  for (const auto& [i, e] : gpu) {
    ASSERT_TRUE(cpu.distance.count(i)) << "page " << i;
    const float d = cpu.distance.at(i);
    if (e == 1.0f) {
      ++allocated;
      if (i < coarsest_start) farthest_kept = std::max(farthest_kept, d);
    } else {
      ++dropped;
      EXPECT_LT(i, coarsest_start) << "a coarsest-level page dropped";
      nearest_dropped = std::min(nearest_dropped, d);
    }
    coarsest += i >= coarsest_start;
  }
  std::printf("overflow: %d allocated, %d dropped (%d coarsest-level pages)\n", allocated, dropped,
              coarsest);
  EXPECT_EQ(allocated, 16);
  EXPECT_GT(dropped, 10);
  EXPECT_LE(coarsest, 16);
  EXPECT_LE(farthest_kept, nearest_dropped * (1.0f + 1e-4f));
  // The dropped pages' pixels fall back to the coarsest level; none is left without a page.
  int fell_back = 0, no_page = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      fell_back += fallback.at(x, y) == 0.5f;
      no_page += fallback.at(x, y) == 1.0f;
      EXPECT_TRUE(v.at(x, y) >= 0.0f && v.at(x, y) <= 1.0f);
    }
  EXPECT_GT(fell_back, 100);
  EXPECT_EQ(no_page, 0);
}

// The timing contract under the sun: check-technique's checks, with the sun turned.
TEST_F(VirtualShadowMapRender, KeepsTheTimingContractUnderTheSun) {
  stage_ = std::make_unique<ContractStage>(sun_scene(), 96, 72, std::vector{info_}, plugins_);
  const core::AreaLight first = stage_->scene().light;
  for (const char* filter : {"hard", "pcf"}) {
    const Params p = resolve_params(info_->params, {{"filter", filter}, {"size", 1024}}, "", "");
    const auto create = [&] { return info_->create(p); };
    const core::AreaLight second =
        core::make_sun_light(glm::normalize(kToSun + glm::vec3(-0.2f, 0.0f, 0.1f)), first.target,
                             first.angular_diameter, 80.0f);
    const ContractStage::Frames f = stage_->across_a_move(
        create, [&] { stage_->set_light(first); }, [&] { stage_->set_light(second); });
    stage_->set_light(first);
    EXPECT_EQ(run::differing_pixels(f.a_moved, f.b_moved), 0u) << filter;
    EXPECT_GT(run::differing_pixels(f.a_first, f.a_moved), 0u) << filter;
    for (const run::ContractCheck& c :
         {run::check_camera_move(*stage_, create, true),
          run::check_visibility_written(*stage_, create), run::check_deterministic(*stage_, create),
          run::check_gbuffer_untouched(*stage_, create)})
      EXPECT_TRUE(c.passed()) << filter << ": " << c.name << ": " << c.failure;
  }
}

// Its memory: the pool (size² 32-bit depths), the page table and the mark
// buffer (4 bytes per page of every level), made through the metered makers.
TEST_F(VirtualShadowMapRender, ItsGpuMemoryIsThePoolThePageTableAndTheMarks) {
  const gl::AllocationWindow window;
  const auto t = info_->create(resolve_params(
      info_->params, {{"size", 1024}, {"virtual_size", 8192}, {"page_size", 128}, {"levels", 6}},
      "", ""));
  t->prepare(stage_->inputs());
  const std::int64_t pages = 6 * 64 * 64;
  EXPECT_EQ(window.live_bytes(), std::int64_t(1024) * 1024 * 4 + 2 * pages * 4);
}

}  // namespace
}  // namespace sb::test
