#include "reference/reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"
#include "reference/adaptive.h"
#include "reference/cache_file.h"
#include "reference/distinct_casters.h"
#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/exact_visibility.h"
#include "reference/key_lock.h"
#include "reference/method.h"
#include "reference/pixel_rays.h"
#include "reference/settled.h"
#include "reference/stratify.h"
#include "reference/uniform_trace.h"
#include "scenes/topology.h"

namespace sb::reference {

using core::AnalyticShape;
using core::AreaLight;
using core::Camera;
using core::ImageF;
using core::JobError;
using core::Mesh;
using core::Scene;
using core::write_file_atomically;

namespace {

using detail::Device;
using detail::embree_config_of;
using detail::FlatScene;
using detail::FtzDazScope;
using detail::method_of;
using detail::Settled;

void check_inputs(const ImageF& positions, const ImageF& normals, const Settings& s) {
  if (s.spp < 1 || s.spp > kMaxSpp)
    throw std::invalid_argument("reference: spp must be in [1, 2^20], got " +
                                std::to_string(s.spp));
  check_embree_config(embree_config_of(s));
  if (s.adaptive && !s.exact) {
    if (const std::string why = detail::adaptive_layout_problem(s.spp, s.pilot_spp); !why.empty())
      throw std::invalid_argument("reference: adaptive sampling: " + why);
    if (!(s.target_std_error > 0.0 && s.target_std_error <= 0.5))
      throw std::invalid_argument("reference: target_std_error must be in (0, 0.5]");
  }
  if (positions.channels != 4)
    throw std::invalid_argument("reference: positions must have 4 channels (xyz, coverage)");
  if (normals.channels < 3)
    throw std::invalid_argument("reference: normals must have at least 3 channels");
  if (positions.width != normals.width || positions.height != normals.height)
    throw std::invalid_argument("reference: positions and normals differ in size");
  if (positions.width < 0 || positions.height < 0 ||
      positions.data.size() != positions.pixel_count() * 4 ||
      normals.data.size() != normals.pixel_count() * size_t(normals.channels))
    throw std::invalid_argument("reference: image data does not match its shape");
}

using detail::covered;

void summarise(Result& r, const ImageF& positions, const Settings& s) {
  double sum = 0, stop_sum = 0, psum = 0, psum2 = 0;
  int64_t estimates = 0, stops = 0, pcount = 0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    if (!covered(positions, i)) continue;
    const float v = r.visibility.data[i];
    if (v > 0.0f && v < 1.0f) {
      sum += r.std_error.data[i];
      ++estimates;
    } else if (r.stop_bound.data[i] > 0.0f) {
      stop_sum += r.stop_bound.data[i];
      ++stops;
    }
    if (r.penumbra[i]) {
      const double noise = std::max(r.std_error.data[i], r.stop_bound.data[i]);
      psum += noise;
      psum2 += noise * noise;
      ++pcount;
    }
  }
  r.mean_std_error = estimates ? sum / double(estimates) : 0.0;
  r.estimate_pixels = estimates;
  r.stopped_pixels = stops;
  r.mean_stop_bound = stops ? stop_sum / double(stops) : 0.0;
  r.penumbra_mean_std_error = pcount ? psum / double(pcount) : 0.0;
  r.penumbra_rms_std_error = pcount ? std::sqrt(psum2 / double(pcount)) : 0.0;
  double samples = 0;
  float most = 0;
  int64_t count = 0;
  for (size_t i = 0; i < positions.pixel_count() && !r.samples.data.empty(); ++i) {
    if (!covered(positions, i)) continue;
    samples += r.samples.data[i];
    most = std::max(most, r.samples.data[i]);
    ++count;
  }
  r.mean_spp = count ? samples / double(count) : 0.0;
  r.max_spp = int(most);
  if (r.method == kAdaptiveMethod) {
    r.unproven_stops = int64_t(detail::unproven_stops(r.samples, r.stop_bound, s.pilot_spp));
    r.stop_bias_bound = r.unproven_stops > 0 ? detail::stop_bias_bound(s.pilot_spp) : 0.0;
  }
}

// spp on every covered pixel, 0 elsewhere: a uniform reference's samples.
ImageF uniform_samples(const ImageF& positions, int spp) {
  ImageF out(positions.width, positions.height, 1, 0.0f);
  for (size_t i = 0; i < positions.pixel_count(); ++i)
    if (covered(positions, i)) out.data[i] = float(spp);
  return out;
}

// A segment light is stratified along its one axis (stratify.h); rectangles
// and points keep the square cells.
detail::Strata strata_of(const AreaLight& light) {
  if (!light.is_segment()) return detail::Strata::Square;
  return light.width() > 0.0f ? detail::Strata::AlongS : detail::Strata::AlongT;
}

// What the cache file of `key` must say to be the reference `s` asks for.
detail::CacheFileExpectation cache_expectation(const std::string& key, const ImageF& positions,
                                               const Settings& s) {
  detail::CacheFileExpectation e;
  e.key = key;
  e.method = method_of(s);
  e.width = positions.width;
  e.height = positions.height;
  e.spp = s.exact ? 0 : s.spp;
  e.seed = s.seed;
  if (s.adaptive && !s.exact)  // the pilot's samples come on top of the estimate's
    e.max_samples = float(s.spp + s.pilot_spp);
  return e;
}

// Per mesh, whether it is a closed caster (ExactVisibility's constructor).
// An alpha-masked mesh never is: its mask cuts holes in it.
std::vector<bool> closed_casters(const Scene& scene) {
  std::vector<bool> closed;
  for (const Mesh& m : scene.meshes)
    closed.push_back(m.casts_shadow && !m.double_sided && !m.alpha_tested() &&
                     analyse_topology(m).closed());
  return closed;
}

// Whether the adaptive reference's proofs (adaptive.h) hold for the scene's
// casters: a rectangular light, and every caster inside its triangles. An
// alpha-masked caster is (its mask only takes parts away), so "no triangle
// meets the pyramid" still proves a pilot lit, and, never closed, it proves
// none occluded. An analytic shape bulges out of its triangles.
bool proofs_hold(const Scene& scene) {
  if (scene.light.is_segment() || scene.light.is_point() || scene.light.is_sun()) return false;
  return std::none_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) {
    return m.casts_shadow && m.analytic.kind != AnalyticShape::Kind::None;
  });
}

// Result::penumbra of a Monte Carlo estimate (reference.h): a soft estimate
// proves a pixel soft; one whose samples all agreed asks `exact` (null: the
// scene has no exact form, and the soft estimates are the region), unless
// tracing settled it (settled.h; empty: nothing settled).
void find_penumbra(const ImageF& positions, const ImageF& normals, const ExactVisibility* exact,
                   const std::vector<Settled>& settled, Result& r) {
  const size_t n = positions.pixel_count();
  r.penumbra.assign(n, 0);
  r.penumbra_source = exact != nullptr ? kPenumbraExact : kPenumbraSampled;
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& b) {
        for (size_t i = b.begin(); i < b.end(); ++i) {
          if (!covered(positions, i)) continue;
          const float v = r.visibility.data[i];
          if (v > 0.0f && v < 1.0f) {
            r.penumbra[i] = 1;
            continue;
          }
          const Settled known = settled.empty() ? Settled::Unknown : settled[i];
          if (exact == nullptr || known == Settled::Proven) continue;
          const float* p = &positions.data[i * 4];
          const float* q = &normals.data[i * size_t(normals.channels)];
          const glm::dvec3 point(p[0], p[1], p[2]), normal(q[0], q[1], q[2]);
          if (known == Settled::Unknown) {
            r.penumbra[i] = exact->partly_lit(point, normal) ? 1 : 0;
          } else {  // partly_lit without the proofs, which cannot hold here
            const double exact_v = exact->visibility(point, normal);
            r.penumbra[i] = exact_v > kPartlyLitMargin && exact_v < 1.0 - kPartlyLitMargin ? 1 : 0;
          }
        }
      });
}

}  // namespace

Result compute(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
               const Settings& s) {
  check_inputs(positions, geometric_normals, s);
  {
    // A caster repeated exactly hides nothing more: traced once
    // (distinct_casters.h), V unchanged, its time counted.
    const auto t0 = std::chrono::steady_clock::now();
    if (std::optional<Scene> distinct = detail::without_repeated_casters(scene)) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      Result r = compute(*distinct, positions, geometric_normals, s);
      r.seconds += seconds;
      return r;
    }
  }
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    if (!covered(positions, i)) continue;
    const float* p = &positions.data[i * 4];
    const float* n = &geometric_normals.data[i * size_t(geometric_normals.channels)];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) ||
        !std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]))
      throw std::invalid_argument("reference: non-finite position or normal at pixel (" +
                                  std::to_string(i % size_t(positions.width)) + ", " +
                                  std::to_string(i / size_t(positions.width)) + ")");
  }

  if (s.exact) {
    const std::string why = ExactVisibility::unsupported_reason(scene);
    if (!why.empty()) {
      Settings sampled = s;
      sampled.exact = false;
      Result r = compute(scene, positions, geometric_normals, sampled);
      r.exact_fallback = why;
      return r;
    }
    Result r;
    r.seed = s.seed;
    r.method = kExactMethod;
    const auto t0 = std::chrono::steady_clock::now();
    // Closed casters keep only the triangles that face the point, part by
    // part (exact_visibility.h): right whichever way each part winds.
    const ExactVisibility exact(scene, closed_casters(scene));
    r.visibility = exact.image(positions, geometric_normals);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.std_error = ImageF(positions.width, positions.height, 1, 0.0f);
    r.stop_bound = r.std_error;
    r.samples = r.std_error;
    r.penumbra.assign(positions.pixel_count(), 0);
    r.penumbra_source = kPenumbraExact;
    for (size_t i = 0; i < positions.pixel_count(); ++i) {
      const double v = r.visibility.data[i];
      r.penumbra[i] = covered(positions, i) && v > kPartlyLitMargin && v < 1.0 - kPartlyLitMargin;
    }
    summarise(r, positions, s);
    return r;
  }

  Result r;
  r.visibility = ImageF(positions.width, positions.height, 1, 1.0f);
  r.std_error = ImageF(positions.width, positions.height, 1, 0.0f);
  r.stop_bound = r.std_error;
  r.spp = s.spp;
  r.seed = s.seed;
  r.method = kStratifiedMethod;
  r.isa = resolve_isa(embree_config_of(s));

  const auto t0 = std::chrono::steady_clock::now();
  std::optional<ExactVisibility> exact;
  std::vector<detail::Settled> settled;
  {
    Device device(r.isa);
    FlatScene casters(
        device, scene, [](const Mesh& m) { return m.casts_shadow; }, /*analytic_shapes=*/true);
    // The exact visibility decides the penumbra (and proves the adaptive
    // reference's agreeing pilots) where the scene has an exact form; made
    // after the flat scene, which refuses broken caster geometry first.
    if (ExactVisibility::unsupported_reason(scene).empty() || (s.adaptive && proofs_hold(scene)))
      exact.emplace(scene, closed_casters(scene));
    const detail::Strata strata = strata_of(scene.light);
    const detail::Layout layout = detail::make_layout(s.spp, strata);
    const detail::RaySetup setup(scene, casters, layout, positions, geometric_normals, s.seed);
    // The proofs that agreeing samples missed nothing; the one for occluded
    // samples needs to know which casters are closed.
    const ExactVisibility* whole_light = proofs_hold(scene) && exact ? &*exact : nullptr;
    if (s.adaptive) {
      detail::AdaptiveImages a =
          detail::trace_adaptive(setup, strata, s.pilot_spp, s.target_std_error, whole_light);
      r.visibility = std::move(a.visibility);
      r.std_error = std::move(a.std_error);
      r.stop_bound = std::move(a.stop_bound);
      r.samples = std::move(a.samples);
      settled = std::move(a.settled);
      r.method = kAdaptiveMethod;
    } else {
      detail::UniformImages u = detail::trace_uniform(setup, whole_light);
      r.visibility = std::move(u.visibility);
      r.std_error = std::move(u.std_error);
      r.stop_bound = std::move(u.stop_bound);
      settled = std::move(u.settled);
      r.samples = uniform_samples(positions, s.spp);
    }
    device.check("rtcOccluded16");
  }
  find_penumbra(positions, geometric_normals,
                exact && exact->unsupported().empty() ? &*exact : nullptr, settled, r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  summarise(r, positions, s);
  return r;
}

Result get(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
           const Settings& s, const std::string& cache_dir) {
  check_inputs(positions, geometric_normals, s);
  if (s.exact) {
    const std::string why = ExactVisibility::unsupported_reason(scene);
    if (!why.empty()) {
      Settings sampled = s;
      sampled.exact = false;
      Result r = get(scene, positions, geometric_normals, sampled, cache_dir);
      r.exact_fallback = why;
      return r;
    }
  }
  const std::string key = cache_key(scene, positions, geometric_normals, s);
  const std::filesystem::path path = std::filesystem::path(cache_dir) / (key + ".sbref");
  const detail::CacheFileExpectation expected = cache_expectation(key, positions, s);
  const auto from_cache = [&]() -> std::optional<Result> {
    std::string bytes;
    Result cached;
    if (!detail::read_cache_file(path, bytes) ||
        !detail::decode_cache_file(bytes, expected, cached))
      return std::nullopt;
    if (!expected.max_samples) cached.samples = uniform_samples(positions, expected.spp);
    cached.spp = s.exact ? 0 : s.spp;
    cached.seed = s.seed;
    cached.method = method_of(s);
    cached.isa = s.exact ? "" : resolve_isa(embree_config_of(s));
    cached.from_cache = true;
    cached.cache_key = key;
    summarise(cached, positions, s);
    return cached;
  };
  if (auto cached = from_cache()) return std::move(*cached);

  std::error_code ec;
  std::filesystem::create_directories(cache_dir, ec);
  if (ec) throw JobError("reference cache: cannot create " + cache_dir + ": " + ec.message());
  // One computation per key across processes (the shards of a run sharing
  // --cache-dir): the first to take the key's lock computes, the others
  // wait and then read its file.
  const detail::KeyLock lock(std::filesystem::path(cache_dir) / (key + ".lock"));
  if (auto cached = from_cache()) return std::move(*cached);
  Result r = compute(scene, positions, geometric_normals, s);
  r.cache_key = key;
  write_file_atomically(path.string(), detail::encode_cache_file(r), "reference cache: ");
  return r;
}

GBuffer trace_gbuffer(const Scene& scene, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("trace_gbuffer: empty image");
  GBuffer g{ImageF(width, height, 4, 0.0f), ImageF(width, height, 3, 0.0f)};
  Device device(resolve_isa(default_embree_config()));
  FlatScene all(device, scene, [](const Mesh&) { return true; });
  if (all.empty()) return g;

  const Camera& cam = scene.camera;
  const glm::mat3 to_world(glm::inverse(cam.view()));
  const float tan_half = std::tan(glm::radians(cam.fov_y_degrees) * 0.5f);
  const float aspect = float(width) / float(height);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    FtzDazScope ftz;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width; ++x) {
        const float ndc_x = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
        const float ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(height);
        // z = -1 in view space, so t is the view-space depth.
        const glm::vec3 d =
            to_world * glm::vec3(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0f);
        RTCRayHit rh;
        rh.ray.org_x = cam.eye.x;
        rh.ray.org_y = cam.eye.y;
        rh.ray.org_z = cam.eye.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = cam.near_plane;
        rh.ray.tfar = cam.far_plane;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xffffffffu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(all.get(), &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const Mesh& m = scene.meshes[all.mesh_of_geometry[rh.hit.geomID]];
        const size_t tri = size_t(rh.hit.primID) * 3;
        const glm::vec3 v0 = m.positions[m.indices[tri]], v1 = m.positions[m.indices[tri + 1]],
                        v2 = m.positions[m.indices[tri + 2]];
        // Interpolate on the triangle rather than org + t*dir: the point lies on it.
        const glm::vec3 p = (1.0f - rh.hit.u - rh.hit.v) * v0 + rh.hit.u * v1 + rh.hit.v * v2;
        const glm::vec3 c = glm::cross(v1 - v0, v2 - v0);
        const float len = glm::length(c);
        glm::vec3 n = len > 0.0f ? c / len : glm::vec3(0.0f);
        // Facing the viewer, as the rasterised G-buffer's (the seen side).
        if (glm::dot(n, d) > 0.0f) n = -n;
        float* pp = &g.positions.at(x, y);
        pp[0] = p.x;
        pp[1] = p.y;
        pp[2] = p.z;
        pp[3] = 1.0f;
        float* np = &g.normals.at(x, y);
        np[0] = n.x;
        np[1] = n.y;
        np[2] = n.z;
      }
  });
  device.check("rtcIntersect1");
  return g;
}

}  // namespace sb::reference
