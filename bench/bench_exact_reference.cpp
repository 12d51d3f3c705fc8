// The exact reference (harness/reference/exact_visibility.h) on the default
// sphere grid (81 UV spheres of 760 triangles over a ground plane), 800×600
// G-buffer made by primary ray casting (not timed), beside the Monte Carlo
// reference at 256 and 1024 spp; and the polygon union it needs, by Clipper
// (integer coordinates, the library it uses) and by Boost.Geometry
// (floating point, union_ one polygon at a time), on the polygon sets of the
// grid's penumbra pixels; and the exact reference against triangle count on
// the jeep scene, 1 to 64 jeeps of 3,620 triangles, beside Monte Carlo at
// 256 spp; and the sphere grid under a linear light (its light 2 × 0): the
// exact reference, and Monte Carlo stratified along the segment against
// square cells on the same segment, with their error against the exact one.
//
// BM_ExactOverMonteCarlo is the exact reference's time over the 256-spp
// Monte Carlo reference's (issue 65: at most 1), on the sphere grid and on
// 1 and 16 jeeps, the two taking turns in one process (the order swaps
// every iteration), so that a loaded machine slows both alike:
//   build/bench/bench_exact_reference --benchmark_filter=Over --benchmark_repetitions=5
#include <benchmark/benchmark.h>

// Boost 1.74's rescaling of coordinates before an overlay reads an
// uninitialised factor (GCC 12 and clang-tidy both say so); without it the
// overlay works in the input's doubles.
#define BOOST_GEOMETRY_NO_ROBUSTNESS
#include <sys/resource.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <chrono>
#include <cmath>
#include <map>
#include <vector>

#include "reference/exact_visibility.h"
#include "reference_workload.h"

namespace {

namespace bg = boost::geometry;
using BoostPoint = bg::model::d2::point_xy<double>;
using BoostPolygon = bg::model::polygon<BoostPoint, /*clockwise=*/false>;
using BoostMulti = bg::model::multi_polygon<BoostPolygon>;
using Polygons = std::vector<std::vector<glm::dvec2>>;

const sb::bench::SceneWorkload& grid() {
  static const sb::bench::SceneWorkload w = sb::bench::default_sphere_grid();
  return w;
}

// The occluding polygons of every 7th penumbra pixel of the sphere grid (of
// the Monte Carlo reference at 64 spp), for the union benchmarks.
const std::vector<Polygons>& penumbra_sets() {
  static const std::vector<Polygons> sets = [] {
    std::vector<Polygons> out;
    const sb::bench::SceneWorkload& w = grid();
    const sb::reference::GBuffer& g = w.gbuffer;
    const sb::reference::Result mc =
        sb::reference::compute(w.scene, g.positions, g.normals, {64, 1});
    const sb::reference::ExactVisibility exact(w.scene);
    size_t penumbra = 0;
    for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
      const float* p = &g.positions.data[i * 4];
      const float v = mc.visibility.data[i];
      if (!(p[3] > 0.5f) || v <= 0.0f || v >= 1.0f || penumbra++ % 7 != 0) continue;
      const float* n = &g.normals.data[i * size_t(g.normals.channels)];
      out.push_back(
          exact.occluding_polygons(glm::dvec3(p[0], p[1], p[2]), glm::dvec3(n[0], n[1], n[2])));
    }
    return out;
  }();
  return sets;
}

// As the harness computes it: BVH build, closedness, the whole image.
void BM_ExactReference(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = grid();
  sb::reference::Settings settings;
  settings.exact = true;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
  }
  state.counters["covered_px"] = double(w.covered);
}
BENCHMARK(BM_ExactReference)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MonteCarloReference(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = grid();
  const sb::reference::Settings settings{int(state.range(0)), 1};
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
  }
}
BENCHMARK(BM_MonteCarloReference)
    ->ArgName("spp")
    ->Arg(256)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// `count` jeeps, built and traced once per count.
const sb::bench::SceneWorkload& jeeps(int count) {
  static std::map<int, sb::bench::SceneWorkload> cache;
  auto it = cache.find(count);
  if (it == cache.end())
    it = cache.emplace(count, sb::bench::scene_workload("jeep", {{"count", count}})).first;
  return it->second;
}

void BM_ExactReferenceJeeps(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = jeeps(int(state.range(0)));
  sb::reference::Settings settings;
  settings.exact = true;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
  }
  state.counters["caster_triangles"] =
      double(sb::reference::ExactVisibility(w.scene).triangle_count());
}
BENCHMARK(BM_ExactReferenceJeeps)
    ->ArgName("jeeps")
    ->RangeMultiplier(4)
    ->Range(1, 64)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_MonteCarloReferenceJeeps(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = jeeps(int(state.range(0)));
  const sb::reference::Settings settings{256, 1};
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
  }
}
BENCHMARK(BM_MonteCarloReferenceJeeps)
    ->ArgName("jeeps")
    ->RangeMultiplier(4)
    ->Range(1, 64)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The process's user + system time, all threads: on a shared machine it
// counts only the time this process ran, unlike wall time.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

// Argument: 0 for the sphere grid, else that many jeeps. Time: the exact
// reference's (manual). Counters: exact_s and mc256_s, each's wall time
// per iteration; exact_over_mc256, their ratio of total wall times, and
// exact_over_mc256_cpu, of total process CPU times.
void BM_ExactOverMonteCarlo(benchmark::State& state) {
  const int count = int(state.range(0));
  const sb::bench::SceneWorkload& w = count == 0 ? grid() : jeeps(count);
  sb::reference::Settings exact;
  exact.exact = true;
  const sb::reference::Settings mc{256, 1};
  double wall[2] = {0.0, 0.0}, cpu[2] = {0.0, 0.0};
  bool exact_first = true;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    double exact_wall = 0.0;
    for (const int which : {exact_first ? 0 : 1, exact_first ? 1 : 0}) {
      const double cpu0 = process_cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      const sb::reference::Result r = sb::reference::compute(
          w.scene, w.gbuffer.positions, w.gbuffer.normals, which == 0 ? exact : mc);
      benchmark::DoNotOptimize(r.visibility.data.data());
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      wall[which] += seconds;
      cpu[which] += process_cpu_seconds() - cpu0;
      if (which == 0) exact_wall = seconds;
    }
    state.SetIterationTime(exact_wall);
    exact_first = !exact_first;
  }
  const double iterations = double(state.iterations());
  state.counters["exact_s"] = wall[0] / iterations;
  state.counters["mc256_s"] = wall[1] / iterations;
  state.counters["exact_over_mc256"] = wall[1] > 0.0 ? wall[0] / wall[1] : 0.0;
  state.counters["exact_over_mc256_cpu"] = cpu[1] > 0.0 ? cpu[0] / cpu[1] : 0.0;
  state.counters["covered_px"] = double(w.covered);
}
BENCHMARK(BM_ExactOverMonteCarlo)
    ->ArgName("jeeps")
    ->Arg(0)
    ->Arg(1)
    ->Arg(16)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// The default sphere grid's light is 2×2: half sizes 1.
double clipper_union_area(const Polygons& set) {
  return sb::reference::ExactVisibility::union_area(set, 1.0, 1.0);
}

double boost_union_area(const Polygons& set) {
  BoostMulti united;
  for (const auto& polygon : set) {
    BoostPolygon b;
    for (const glm::dvec2& q : polygon) bg::append(b.outer(), BoostPoint(q.x, q.y));
    bg::correct(b);
    BoostMulti next;
    bg::union_(united, b, next);
    united = std::move(next);
  }
  return bg::area(united);
}

void BM_UnionClipper(benchmark::State& state) {
  const std::vector<Polygons>& sets = penumbra_sets();
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    double sum = 0.0;
    for (const Polygons& set : sets) sum += clipper_union_area(set);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["sets"] = double(sets.size());
}
BENCHMARK(BM_UnionClipper)->Unit(benchmark::kMillisecond);

void BM_UnionBoostGeometry(benchmark::State& state) {
  const std::vector<Polygons>& sets = penumbra_sets();
  double worst = 0.0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    double sum = 0.0;
    for (const Polygons& set : sets) sum += boost_union_area(set);
    benchmark::DoNotOptimize(sum);
  }
  // How far the two libraries' areas lie apart (as a fraction of the 2×2
  // light's area 4), and on how many sets by more than 1e-6.
  double differ = 0.0;
  for (const Polygons& set : sets) {
    const double d = std::abs(boost_union_area(set) - clipper_union_area(set)) / 4.0;
    worst = std::max(worst, d);
    differ += d > 1e-6;
  }
  state.counters["sets"] = double(sets.size());
  state.counters["sets_differing"] = differ;
  state.counters["max_area_difference"] = worst;
}
BENCHMARK(BM_UnionBoostGeometry)->Unit(benchmark::kMillisecond);

// The default sphere grid under a linear light: its 2×2 light's half_v
// dropped (`light.size: [2, 0]`), or (`rectangle`) kept at 1e-6 of half_u,
// a rectangle that samples the same segment with square cells; with the
// segment's exact reference to measure the Monte Carlo error against.
struct SegmentWorkload {
  sb::bench::SceneWorkload grid;
  sb::core::Scene rectangle;
  sb::core::ImageF exact;
};

const SegmentWorkload& segment_grid() {
  static const SegmentWorkload w = [] {
    SegmentWorkload out{sb::bench::default_sphere_grid(), {}, {}};
    out.rectangle = out.grid.scene;
    out.grid.scene.light.half_v = glm::vec3(0.0f);
    out.rectangle.light.half_v *= 1e-6f;
    sb::reference::Settings settings;
    settings.exact = true;
    out.exact = sb::reference::compute(out.grid.scene, out.grid.gbuffer.positions,
                                       out.grid.gbuffer.normals, settings)
                    .visibility;
    return out;
  }();
  return w;
}

void BM_ExactReferenceSegment(benchmark::State& state) {
  const SegmentWorkload& w = segment_grid();
  sb::reference::Settings settings;
  settings.exact = true;
  size_t penumbra = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r = sb::reference::compute(w.grid.scene, w.grid.gbuffer.positions,
                                                           w.grid.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
    penumbra = 0;
    for (const float v : r.visibility.data) penumbra += v > 0.0f && v < 1.0f;
  }
  state.counters["covered_px"] = double(w.grid.covered);
  state.counters["penumbra_px"] = double(penumbra);
}
BENCHMARK(BM_ExactReferenceSegment)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arguments: spp, and 0 for the segment (strata along it) or 1 for the
// 1e-6-deep rectangle (square cells). Counters: the RMSE against the exact
// reference over its penumbra, and the RMS of the stated error there.
void BM_MonteCarloReferenceSegment(benchmark::State& state) {
  const SegmentWorkload& w = segment_grid();
  const sb::core::Scene& scene = state.range(1) == 0 ? w.grid.scene : w.rectangle;
  const sb::reference::Settings settings{int(state.range(0)), 1};
  double err2 = 0.0, se2 = 0.0, count = 0.0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(scene, w.grid.gbuffer.positions, w.grid.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
    err2 = se2 = count = 0.0;
    for (size_t i = 0; i < w.exact.data.size(); ++i) {
      const double v = w.exact.data[i];
      if (!(v > 0.0 && v < 1.0)) continue;
      err2 += std::pow(double(r.visibility.data[i]) - v, 2);
      se2 += std::pow(double(r.std_error.data[i]), 2);
      ++count;
    }
  }
  state.counters["penumbra_rmse"] = count > 0.0 ? std::sqrt(err2 / count) : 0.0;
  state.counters["penumbra_rms_std_error"] = count > 0.0 ? std::sqrt(se2 / count) : 0.0;
}
BENCHMARK(BM_MonteCarloReferenceSegment)
    ->ArgNames({"spp", "rectangle"})
    ->ArgsProduct({{256, 1024}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
