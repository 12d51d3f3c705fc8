#include "run/measurement_basis.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "core/names.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"
#include "run/run_images.h"

namespace sb::run {

using config::Experiment;
using config::ReferenceConfig;
using config::Resolution;
using core::file_safe;
using core::ImageF;
using core::Scene;
using record::AdaptiveReferenceRecord;
using record::ReferenceRecord;

namespace {

// The reference's part of every record of one (scene, resolution).
// `penumbra`: the reference's penumbra, measured pixels only.
ReferenceRecord reference_record(const reference::Result& ref, const ReferenceConfig& config,
                                 const EmbreeChoice& embree, const metrics::Regions& regions,
                                 const std::vector<uint8_t>& penumbra) {
  ReferenceRecord r;
  r.method = ref.method;
  r.exact_fallback = ref.exact_fallback;
  r.spp = ref.spp;
  r.seed = ref.seed;
  r.embree_isa = ref.isa;
  r.embree_config = embree.config;
  r.mean_std_error = ref.mean_std_error;
  r.estimate_pixels = ref.estimate_pixels;
  r.stopped_pixels = ref.stopped_pixels;
  r.mean_stop_bound = ref.mean_stop_bound;
  r.penumbra_source = ref.penumbra_source;
  r.penumbra_mean_std_error = ref.penumbra_mean_std_error;
  r.penumbra_rms_std_error = ref.penumbra_rms_std_error;
  r.penumbra_pixels = metrics::count_ones(penumbra);
  r.attached_shadow_pixels = metrics::count_ones(regions.attached);
  r.horizon_cut_pixels =
      static_cast<std::int64_t>(regions.measured.size()) - metrics::count_ones(regions.measured);
  r.cache_key = ref.cache_key;
  r.from_cache = ref.from_cache;
  r.seconds = ref.seconds;
  if (ref.method == reference::kAdaptiveMethod)
    r.adaptive = AdaptiveReferenceRecord{config.settings.pilot_spp,
                                         config.settings.target_std_error,
                                         ref.mean_spp,
                                         ref.max_spp,
                                         ref.unproven_stops,
                                         ref.stop_bias_bound};
  return r;
}

// How a reference was made, for the log: "256 spp, 1.2 s, mean std error ...".
std::string describe(const reference::Result& ref) {
  const std::string samples = ref.method == reference::kExactMethod ? std::string("exact")
                              : ref.method == reference::kAdaptiveMethod
                                  ? "adaptive, mean " + std::to_string(ref.mean_spp) + " of " +
                                        std::to_string(ref.spp) + " spp"
                                  : std::to_string(ref.spp) + " spp";
  return samples + ", " +
         (ref.from_cache ? std::string("from cache") : std::to_string(ref.seconds) + " s") +
         ", mean std error " + std::to_string(ref.mean_std_error);
}

// The regions of the catalogue this view has (metrics/regions.h).
metrics::Regions regions_of(const MeasurementBasis& b, const Scene& scene, bool distance_thirds,
                            metrics::DistanceScale distance_scale, FrameTargets& targets) {
  metrics::RegionInputs in;
  in.horizon = metrics::classify_light_horizon(b.positions, b.normals, scene.light);
  in.reference_penumbra = b.ref.penumbra;
  const ImageF receiver = targets.read_receiver_mask();
  in.receiver.resize(receiver.data.size());
  for (size_t i = 0; i < receiver.data.size(); ++i) in.receiver[i] = receiver.data[i] != 0.0f;
  in.positions = &b.positions;
  for (int i = 0; i < 3; ++i) in.eye[i] = scene.camera.eye[i];
  in.distance_thirds = distance_thirds;
  in.distance_scale = distance_scale;
  return metrics::make_regions(in);
}

// The reference of `scene` at the G-buffer's points: from the cache when
// there is one.
reference::Result reference_at(const MeasurementBasis& b, const Scene& scene,
                               const reference::Settings& settings) {
  return b.cache_dir.empty() ? reference::compute(scene, b.positions, b.normals, settings)
                             : reference::get(scene, b.positions, b.normals, settings, b.cache_dir);
}

}  // namespace

reference::Result MeasurementBasis::reference_of(const Scene& scene) const {
  return reference_at(*this, scene, settings);
}

MeasurementBasis make_measurement_basis(const Experiment& e, const RunOptions& o,
                                        const EmbreeChoice& embree, RunEvents& events,
                                        const std::string& scene_name, const Scene& scene,
                                        const Resolution& res, FrameTargets& targets) {
  MeasurementBasis b;
  b.positions = targets.read_positions();
  b.normals = targets.read_geometric_normals();
  // Reference at the G-buffer's very points.
  b.settings = reference_settings(e.reference, embree, e.reference.settings.exact);
  b.cache_dir = e.reference.cache ? o.cache_dir : std::string();
  const auto make_reference = [&](const reference::Settings& settings, const char* which) {
    reference::Result out = reference_at(b, scene, settings);
    // The key names the reference in the record even when nothing is
    // cached, so that `compare` can tell two references apart.
    if (out.cache_key.empty()) {
      reference::Settings keyed = settings;
      if (!out.exact_fallback.empty()) keyed.exact = false;  // as reference::get keys it
      out.cache_key = reference::cache_key(scene, b.positions, b.normals, keyed);
    }
    events.log(std::string(which) + " " + scene_name + " @ " + res.label() + ": " + describe(out));
    if (!out.exact_fallback.empty())
      events.log(std::string(which) + " " + scene_name +
                 ": Monte Carlo, not exact: " + out.exact_fallback);
    return out;
  };
  events.phase(scene_name, res.label(), "(reference)");
  b.ref = make_reference(b.settings, "reference");
  if (e.reference.second_exact) {
    events.phase(scene_name, res.label(), "(second reference)");
    b.second = make_reference(reference_settings(e.reference, embree, *e.reference.second_exact),
                              "second reference");
  }
  b.regions = regions_of(b, scene, e.distance_thirds, e.distance_scale, targets);
  metrics::Regions& regions = b.regions;
  metrics::apply_attached_shadow(regions.attached, b.ref.visibility);
  if (b.second) {
    metrics::apply_attached_shadow(regions.attached, b.second->visibility);
    b.second_record = reference_record(*b.second, e.reference, embree, regions,
                                       metrics::mask_and(b.second->penumbra, regions.measured));
    b.second_flip =
        std::make_shared<metrics::FlipReference>(b.second->visibility, e.flip_pixels_per_degree);
  }
  b.ref_shaded = [&] {
    targets.upload_visibility(b.ref.visibility);
    targets.render_shading(scene);
    return targets.read_shaded();
  }();
  b.prepared = std::make_shared<metrics::PreparedReference>(b.ref.visibility, b.ref_shaded,
                                                            e.flip_pixels_per_degree);
  b.ref_images =
      write_reference_images(o, "reference/" + file_safe(scene_name) + "__" + res.label(), b.ref,
                             b.ref_shaded, regions, b.positions, b.normals);
  b.ref_record = reference_record(b.ref, e.reference, embree, regions, regions.mask("penumbra"));
  return b;
}

}  // namespace sb::run
