// Fingerprints of the Monte Carlo reference's images on the generated scenes
// (uniform and adaptive; defaults, 320×240, plus the 800×600 sphere grid of
// bench_reference): one FNV-1a hash per image (visibility, std_error,
// stop_bound, samples, penumbra). For checking that a change to how the
// reference traces leaves its answer bit for bit the same: run it with two
// builds' libraries and diff the outputs, e.g.
//   build/bench/reference_fingerprint > after.txt
//   LD_LIBRARY_PATH=<other build>/harness build/bench/reference_fingerprint > before.txt
// (it calls only reference::compute and trace_gbuffer, whose interface both
// must share).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/image.h"
#include "reference/reference.h"
#include "reference_workload.h"

namespace {

uint64_t fnv1a(const void* data, size_t bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

uint64_t hash_of(const sb::core::ImageF& image) {
  return fnv1a(image.data.data(), image.data.size() * sizeof(float));
}

void print(const std::string& what, const sb::bench::SceneWorkload& w,
           const sb::reference::Settings& s) {
  const sb::reference::Result r =
      sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, s);
  size_t penumbra = 0;
  for (uint8_t p : r.penumbra) penumbra += p;
  std::printf(
      "%-40s V %016llx  sigma %016llx  stop %016llx  samples %016llx  penumbra %016llx"
      " (%zu px, %s)  %.3f s\n",
      what.c_str(), (unsigned long long)hash_of(r.visibility),
      (unsigned long long)hash_of(r.std_error), (unsigned long long)hash_of(r.stop_bound),
      (unsigned long long)hash_of(r.samples),
      (unsigned long long)fnv1a(r.penumbra.data(), r.penumbra.size()), penumbra,
      r.penumbra_source.c_str(), r.seconds);
  std::fflush(stdout);
}

sb::bench::SceneWorkload at(const std::string& type, int width, int height,
                            const nlohmann::json& overrides = nlohmann::json::object()) {
  sb::bench::SceneWorkload w = sb::bench::scene_workload(type, overrides);
  if (width != 800 || height != 600) {
    w.gbuffer = sb::reference::trace_gbuffer(w.scene, width, height);
    w.covered = 0;
    for (size_t i = 0; i < w.gbuffer.positions.pixel_count(); ++i)
      w.covered += w.gbuffer.positions.data[i * 4 + 3] > 0.5f;
  }
  return w;
}

}  // namespace

int main() {
  {
    const sb::bench::SceneWorkload w = at("sphere_grid", 800, 600);
    print("sphere_grid 800x600 spp64 seed1", w, {64, 1});
    print("sphere_grid 800x600 spp64 seed2", w, {64, 2});
  }
  struct Case {
    std::string type;
    nlohmann::json overrides;
  };
  const std::vector<Case> cases = {
      {"sphere_grid", nlohmann::json::object()},    {"sphere_grid", {{"analytic", true}}},
      {"jeep", nlohmann::json::object()},           {"foliage", nlohmann::json::object()},
      {"plates", nlohmann::json::object()},         {"standing", nlohmann::json::object()},
      {"long_ground", nlohmann::json::object()},    {"outdoor", nlohmann::json::object()},
      {"stress_geometry", nlohmann::json::object()}};
  for (const Case& c : cases) {
    const sb::bench::SceneWorkload w = at(c.type, 320, 240, c.overrides);
    const std::string name = c.type + (c.overrides.empty() ? "" : c.overrides.dump());
    for (int spp : {4, 16, 64, 256}) print(name + " spp" + std::to_string(spp), w, {spp, 3});
    sb::reference::Settings adaptive{1024, 3};
    adaptive.adaptive = true;
    adaptive.pilot_spp = 4;
    adaptive.target_std_error = 0.02;
    print(name + " adaptive1024/4", w, adaptive);
  }
  return 0;
}
