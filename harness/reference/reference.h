#pragma once
// Ray-traced reference visibility at the G-buffer's surface points.
//
// For each covered pixel (positions.w > 0.5) V is the fraction of the
// rectangular area light (or, for a linear light, of the segment's length)
// visible from the point, with only meshes whose
// casts_shadow is true as occluders (receivers never occlude). Light points
// below the surface's tangent plane count as occluded by the surface itself
// (no cosine weight: that belongs to shading). Background pixels get V = 1
// and std error 0.
//
// Analytic shapes: a caster with Mesh::analytic set occludes with that shape
// (an Embree sphere), not with its triangles; the points stay the G-buffer's,
// on the triangles. A tessellation lies inside its sphere, so a ray from one
// of its own points would leave through the sphere: a ray whose origin lies
// within the sphere's radius (plus four ray offsets, embree_scene.cpp) passes
// it. A UV sphere is convex, so a ray that leaves a point above its facet's
// plane (the horizon rule below) never meets the mesh again: the rule keeps
// a mesh's self-shadowing exactly what its triangles give, the facet's
// plane, while every other point (other meshes', the ground) is occluded by
// the exact sphere. (A non-convex mesh inside its sphere would lose the
// shadows it casts on itself.) Points of another mesh inside a sphere, or
// outside it by less than the tolerance (casters that interpenetrate or
// touch), are not occluded by that sphere either.
//
// Sampling: `spp` stratified samples on the light (n×n jittered grid when
// spp = n*n, near-square equal-area cells otherwise; on a segment light, spp
// cells of length 1/spp along it; see stratify.h), drawn
// from a counter-based RNG keyed by (seed, pixel index, spp) (SplitMix64,
// core/counter_rng.h; no std distribution): results are bit-identical for
// any thread count, across calls and with any standard library. Across Embree's ISAs
// they can differ by single rays in a few silhouette pixels: Settings::
// embree_config pins the ISA (embree_isa.h). 16 neighbouring strata of one
// pixel go into one rtcOccluded16 packet (shadow_packet.h says how its unused
// lanes are kept out of every ISA's kernels).
//
// Shadow rays: origin p + eps*n, n the G-buffer's geometric normal, which
// faces the viewer (the seen side of the surface; never flipped towards the
// light, which would start rays inside closed solids), eps = 2^-16 *
// max(max|p_i|, M), M the largest |coordinate| of the caster triangles p lies
// on (ray_offset.h): float rounding at p, never the size of the whole scene.
// Rays end at distance*(1 - 1e-4) before the light sample. Embree traces
// them in robust mode, so that a ray through an edge two caster triangles
// share does not slip between them (embree_scene.h).
//
// Standard error: the collapsed-strata estimate. Horizontally neighbouring
// strata (on a segment, neighbours along it) are paired (a triple closes an
// odd row) and
//   Var = (1/N^2) * sum_groups |g|/(|g|-1) * sum_{i in g} (f_i - mean_g)^2.
// For a 0/1 integrand a pair adds 1 when its two samples disagree. It is
// unbiased for the within-stratum variance plus a non-negative term from the
// difference of neighbouring strata's means, so it is conservative, but far
// tighter than the Bernoulli sqrt(p(1-p)/(N-1)) (it falls as ~N^-0.75 in
// penumbrae like the true error, not N^-0.5). σ averages it over two
// groupings, the pairs above and pairs shifted by one cell, so that an edge
// along the pairs' boundaries, where every pair agrees, still shows; other
// groupings, then the binomial error, stand in where both say 0
// (stratify.h: standard_error): no estimate strictly between 0 and 1
// reports σ = 0. A pixel whose samples all agree has
// no spread to estimate: σ 0, and its stop bound (stratify.h: stop_rms_bound
// of its sample count) beside it, unless a proof (the exact reference, the
// adaptive reference's proofs) says it is exact.
//
// The penumbra (Result::penumbra): the covered pixels that see part of the
// light, 0 < V < 1. Where the exact reference can do the scene's casters and
// light, membership is decided exactly whatever the sample count: an
// estimate strictly between 0 and 1 proves it (one ray reached the light and
// one did not); a pixel whose samples all agreed is asked of the exact
// visibility (exact_visibility.h: partly_lit). Otherwise (alpha-masked or
// analytic casters, a point light) it is the soft estimates, which miss soft
// pixels whose samples happened to agree: Result::penumbra_source says which.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "reference/settings.h"

namespace sb::reference {

// Result::method of the Monte Carlo reference with the same samples on
// every pixel.
inline constexpr const char* kStratifiedMethod = "embree_stratified_packet16";

// Result::method of the adaptive Monte Carlo reference.
inline constexpr const char* kAdaptiveMethod = "embree_stratified_adaptive";

// Result::method of the exact reference (exact_visibility.h).
inline constexpr const char* kExactMethod = "exact_clipper";

// The method that `s` asks for, with the version constants that change its
// numbers when bumped, and the Embree version that traces it: what a run's
// spec hash holds (run/job_identity.h), so that a bump reruns old jobs.
// "embree_stratified_packet16/5 on Embree 3.13.5"; adaptive
// "embree_stratified_adaptive/5.2 on Embree ..." (method version, then the
// adaptive version); exact "exact_clipper/3, else <the Monte Carlo id>",
// since a scene the exact reference cannot do gets Monte Carlo instead.
std::string method_id(const Settings& s);

// Where Result::penumbra comes from.
inline constexpr const char* kPenumbraExact = "exact";      // decided exactly
inline constexpr const char* kPenumbraSampled = "sampled";  // the soft estimates

struct Result {
  core::ImageF visibility;  // 1 channel
  // 1 channel, per pixel: σ, the standard error of an estimate strictly
  // between 0 and 1 (0 elsewhere), and the stop bound of a pixel whose
  // samples all agreed without a proof (0 elsewhere).
  core::ImageF std_error, stop_bound;
  // The covered pixels that see part of the light (1), and how that was
  // decided (kPenumbraExact or kPenumbraSampled).
  std::vector<uint8_t> penumbra;
  std::string penumbra_source;
  double mean_std_error = 0;    // σ over the estimates strictly between 0 and 1
  int64_t estimate_pixels = 0;  // how many those are
  // The covered pixels whose samples all agreed without a proof, and the
  // mean of their stop bounds.
  int64_t stopped_pixels = 0;
  double mean_stop_bound = 0;
  // Over the penumbra, each pixel's noise: its σ, or its stop bound where its
  // samples agreed. The mean, and sqrt(mean of squares): the noise's RMS,
  // the figure an RMSE is comparable with (the mean understates it).
  double penumbra_mean_std_error = 0;
  double penumbra_rms_std_error = 0;
  int spp = 0;
  uint64_t seed = 0;
  // Light samples per pixel (0 off the surfaces): spp everywhere on them
  // but for the adaptive reference (its pilot's included, so up to spp +
  // pilot_spp), which also fills mean_spp and max_spp over the covered
  // pixels.
  core::ImageF samples;
  double mean_spp = 0;
  int max_spp = 0;
  // The adaptive reference's covered pixels stopped at an agreeing pilot
  // without a proof (adaptive.h, the window rule), and the most such a stop
  // can bias a pixel (0 when there is none).
  int64_t unproven_stops = 0;
  double stop_bias_bound = 0;
  std::string method;          // kStratifiedMethod, kAdaptiveMethod or kExactMethod
  std::string exact_fallback;  // why an exact reference asked for is Monte Carlo instead
  std::string isa;     // the Embree ISA that traced it ("avx2"), from Settings::embree_config
  double seconds = 0;  // wall time of BVH build + ray tracing (0 if loaded from cache)
  bool from_cache = false;
  std::string cache_key;
};

// positions: RGBA32F (w = 1 where a surface was hit); geometric_normals: 3 or 4
// channels, same size. Throws std::invalid_argument on bad shapes/settings
// (a malformed embree_config included) or a non-finite covered pixel,
// UnsupportedIsa when the CPU lacks the ISA asked for, sb::InputError on
// broken caster geometry, sb::JobError on Embree failures and on points so far
// out that Embree cannot trace their rays.
Result compute(const core::Scene& scene, const core::ImageF& positions,
               const core::ImageF& geometric_normals, const Settings& s);

// As compute(), but looked up in / stored to cache_dir/<key>.sbref. The key
// hashes everything V depends on (adaptive settings included): caster geometry (in order), the
// light rectangle (centre, half_u, half_v; not target or intensity; for a segment light also a tag
// of its layout along the segment), every caster's analytic shape (kind, centre, radius), both
// buffers' shapes and bytes, the settings, the method and its
// version, and the Embree version and ISA. Corrupt or mismatched files are ignored
// and recomputed; writes go to a temp file renamed into place. Processes
// sharing cache_dir compute each key once: a miss takes the key's lock file
// (<key>.lock, flock) and looks again before computing. An unwritable
// cache_dir throws sb::JobError.
Result get(const core::Scene& scene, const core::ImageF& positions,
           const core::ImageF& geometric_normals, const Settings& s, const std::string& cache_dir);

// The key get() uses (16 hex digits), without computing anything.
std::string cache_key(const core::Scene& scene, const core::ImageF& positions,
                      const core::ImageF& geometric_normals, const Settings& s);

// A G-buffer made by primary ray casting with Embree (all meshes, casters and
// receivers) through scene.camera, pixel centres, row 0 on top, the view-space
// depth limited to [near, far]: positions RGBA32F (w = 1 on a hit), geometric
// normals RGB32F = ±normalize(cross(v1-v0, v2-v0)), the sign that faces the
// camera (as the rasterised G-buffer's: the side that is seen).
// For tests and benchmarks that need the reference without GL.
struct GBuffer {
  core::ImageF positions;
  core::ImageF normals;
};
GBuffer trace_gbuffer(const core::Scene& scene, int width, int height);

}  // namespace sb::reference
