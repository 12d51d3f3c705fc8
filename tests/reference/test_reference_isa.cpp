// The reference under every Embree ISA this CPU runs. rtcOccluded16 takes a
// different path per ISA (native 16-wide kernels on avx512, Embree's ray-stream
// filter below it), so each is run at sample counts that leave packets full
// (16, 256), partly empty (1, 4, 15) and a full one plus a nearly empty one
// (17). ISAs the CPU lacks are skipped, saying so.
//
// What "the same" means: the sphere's silhouette puts rays within float
// rounding of a triangle edge, where the 4-, 8- and 16-wide kernels may round
// differently. So the results are required to be bit-identical in all but a
// few pixels, and where they differ, to differ by few rays: at most 1% of the
// covered pixels may differ, and none by more than max(2/spp, 3 combined
// standard errors), the stratified estimate's own tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/params.h"
#include "core/scene_types.h"
#include "reference/embree_isa.h"
#include "reference/reference.h"
#include "reference/shadow_packet.h"
#include "test_scenes.h"

namespace {

namespace ref = sb::reference;
using sb::core::ImageF;

const int kSpps[] = {1, 4, 15, 16, 17, 256};

struct Workload {
  std::string name;
  sb::core::Scene scene;
  ref::GBuffer g;
  size_t covered = 0;
  Workload(std::string n, sb::core::Scene sc, int w, int h)
      : name(std::move(n)), scene(std::move(sc)), g(ref::trace_gbuffer(scene, w, h)) {
    for (size_t i = 0; i < g.positions.pixel_count(); ++i)
      covered += g.positions.data[i * 4 + 3] > 0.5f;
  }
};

sb::core::Scene default_scene(const char* type, const nlohmann::json& params) {
  const sb::core::SceneType* t = sb::core::find_scene_type(type);
  if (t == nullptr) throw std::runtime_error(std::string("no scene type ") + type);
  nlohmann::json p = nlohmann::json::object();
  for (const auto& d : t->params) p[d.name] = d.default_value;
  p.update(params);
  return t->build(sb::core::Params(p));
}

// A sphere's silhouette over a plane (rays within rounding of triangle
// edges), and two trees with alpha-tested leaves (Embree's filter callback
// gets each kernel's own lane layout).
const std::vector<Workload>& workloads() {
  static const std::vector<Workload> w = [] {
    std::vector<Workload> out;
    out.emplace_back("sphere", sbtest::sphere_over_plane(), 96, 72);
    out.emplace_back(
        "foliage", default_scene("foliage", {{"trees", 2}, {"depth", 2}, {"leaves_per_branch", 6}}),
        96, 72);
    return out;
  }();
  return w;
}

const Workload& workload() { return workloads().front(); }

// The lowest ISA every x86-64 CPU runs: the one the others are held to.
const ref::Result& baseline(const Workload& w, int spp) {
  static std::map<std::pair<std::string, int>, ref::Result> cache;
  const auto key = std::make_pair(w.name, spp);
  auto it = cache.find(key);
  if (it == cache.end())
    it = cache.emplace(key, ref::compute(w.scene, w.g.positions, w.g.normals, {spp, 7, "isa=sse2"}))
             .first;
  return it->second;
}

class referenceIsa : public ::testing::TestWithParam<std::string> {};

TEST_P(referenceIsa, MatchesTheSse2KernelsAtEverySampleCount) {
  const std::string isa = GetParam();
  if (!ref::cpu_supports_isa(isa))
    GTEST_SKIP() << "this CPU lacks " << isa << " (it runs at most " << ref::best_cpu_isa() << ")";
  for (const Workload& w : workloads()) {
    ASSERT_GT(w.covered, w.g.positions.pixel_count() / 4) << w.name;
    for (int spp : kSpps) {
      SCOPED_TRACE(w.name + ", spp " + std::to_string(spp));
      const ref::Result& base = baseline(w, spp);
      const ref::Result r =
          ref::compute(w.scene, w.g.positions, w.g.normals, {spp, 7, "isa=" + isa});
      EXPECT_EQ(r.isa, isa);
      EXPECT_EQ(base.isa, "sse2");
      size_t differing = 0, shadowed = 0;
      for (size_t i = 0; i < r.visibility.data.size(); ++i) {
        const float v = r.visibility.data[i], b = base.visibility.data[i];
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << "pixel " << i << ": " << v;
        if (w.g.positions.data[i * 4 + 3] > 0.5f && v < 1.0f) ++shadowed;
        if (v == b) continue;
        ++differing;
        const double tolerance =
            std::max(2.0 / spp,
                     3.0 * std::hypot(double(r.std_error.data[i]), double(base.std_error.data[i])));
        EXPECT_LE(std::fabs(double(v) - double(b)), tolerance) << "pixel " << i;
      }
      EXPECT_LE(double(differing), 0.01 * double(w.covered));
      // Each scene has a shadow: a kernel that traced nothing would fail here.
      EXPECT_GT(shadowed, w.covered / 50);
      std::printf("%s, %s, spp %d: %zu of %zu covered pixels differ from sse2, %zu shadowed\n",
                  isa.c_str(), w.name.c_str(), spp, differing, w.covered, shadowed);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryEmbreeIsa, referenceIsa,
                         ::testing::Values("sse4.2", "avx", "avx2", "avx512"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           name.erase(std::remove(name.begin(), name.end(), '.'), name.end());
                           return name;
                         });

TEST(referenceIsaChoice, ResolvesAgainstThisCpu) {
  EXPECT_EQ(ref::resolve_isa(""), ref::best_cpu_isa());
  EXPECT_EQ(ref::resolve_isa("isa=sse2"), "sse2");
  EXPECT_EQ(ref::resolve_isa(" isa = SSE42 "), "sse4.2");
  EXPECT_EQ(ref::resolve_isa("max_isa=avx512"), ref::best_cpu_isa());
  EXPECT_EQ(ref::resolve_isa("max_isa=sse2"), "sse2");
  for (const std::string& isa : ref::embree_isas()) {
    if (!ref::cpu_supports_isa(isa)) {
      EXPECT_THROW(ref::resolve_isa("isa=" + isa), ref::UnsupportedIsa) << isa;
    }
  }
  for (const char* bad : {"isa", "isa=", "isa=avx9", "threads=2", "verbose=1", "avx2"})
    EXPECT_THROW(ref::check_embree_config(bad), std::invalid_argument) << bad;
}

TEST(referenceIsaChoice, RecordedIsaIsTheDevicesAndPartOfTheCacheKey) {
  const Workload& w = workload();
  const ref::Result r = ref::compute(w.scene, w.g.positions, w.g.normals, {4, 1, "isa=sse2"});
  EXPECT_EQ(r.isa, "sse2");
  const std::string sse2 = ref::cache_key(w.scene, w.g.positions, w.g.normals, {4, 1, "isa=sse2"});
  EXPECT_EQ(sse2, ref::cache_key(w.scene, w.g.positions, w.g.normals, {4, 1, "max_isa=sse2"}));
  if (ref::cpu_supports_isa("sse4.2")) {
    EXPECT_NE(sse2, ref::cache_key(w.scene, w.g.positions, w.g.normals, {4, 1, "isa=sse4.2"}));
  }
}

// ---- the lanes Embree must skip ---------------------------------------------

TEST(referenceShadowPacket, InactiveLanesAreSkippedByEveryKernelPath) {
  ref::detail::ShadowPacket p;
  p.reset({1, 2, 3});
  p.activate(3, {0, 5, 0}, 0.9999f);
  p.activate(7, {1, 5, 0}, 0.9999f);
  p.deactivate(7);
  for (int j = 0; j < ref::detail::ShadowPacket::kLanes; ++j) {
    SCOPED_TRACE("lane " + std::to_string(j));
    EXPECT_TRUE(std::isfinite(p.ray.dir_x[j]) && std::isfinite(p.ray.dir_y[j]) &&
                std::isfinite(p.ray.dir_z[j]));
    EXPECT_EQ(p.ray.org_y[j], 2.0f);
    if (j == 3) {
      EXPECT_EQ(p.valid[j], -1);
      EXPECT_LE(p.ray.tnear[j], p.ray.tfar[j]);
      EXPECT_GE(p.ray.tfar[j], 0.0f);
      EXPECT_TRUE(p.reached_light(j));
    } else {
      // The stream filter (avx2 and below) reads only tnear/tfar; the native
      // kernels read valid and drop tfar < 0 too.
      EXPECT_EQ(p.valid[j], 0);
      EXPECT_LT(p.ray.tfar[j], 0.0f);
      EXPECT_GT(p.ray.tnear[j], p.ray.tfar[j]);
      EXPECT_FALSE(p.reached_light(j));
    }
  }
}

TEST(referenceShadowPacket, OneSamplePerPixelTracesOneLane) {
  const Workload& w = workload();
  const ref::Result r = ref::compute(w.scene, w.g.positions, w.g.normals, {1, 3});
  size_t zeros = 0, ones = 0;
  for (size_t i = 0; i < r.visibility.data.size(); ++i) {
    const float v = r.visibility.data[i];
    ASSERT_TRUE(v == 0.0f || v == 1.0f) << "pixel " << i << ": " << v;
    if (w.g.positions.data[i * 4 + 3] <= 0.5f) continue;
    (v == 0.0f ? zeros : ones)++;
    // One sample says nothing of its own spread: σ 0, and the bound of one
    // agreeing sample beside it.
    EXPECT_EQ(r.std_error.data[i], 0.0f);
    EXPECT_EQ(r.stop_bound.data[i], float(ref::detail::stop_rms_bound(1)));
  }
  EXPECT_GT(zeros, 0u);
  EXPECT_GT(ones, 0u);
}

// ---- inputs Embree cannot trace fail the job, not the process ------------------

TEST(referenceRayRange, PointsBeyondEmbreesRangeFailTheJob) {
  const Workload& w = workload();
  sb::core::ImageF pos = w.g.positions;
  size_t far_pixel = 0;
  while (pos.data[far_pixel * 4 + 3] <= 0.5f) ++far_pixel;
  pos.data[far_pixel * 4 + 0] = 3e18f;  // finite, but past Embree's 1.8e18
  try {
    (void)ref::compute(w.scene, pos, w.g.normals, {16, 1});
    FAIL() << "expected a JobError";
  } catch (const sb::core::JobError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond what Embree traces"), std::string::npos)
        << e.what();
  }
}

}  // namespace
