#pragma once
// record["reference"]: the ray-traced reference the job was measured
// against (docs/results.md, "reference").
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// record["reference"]["adaptive"], only for the adaptive reference
// (reference.adaptive): its settings, the light samples it took per
// covered pixel (the pilot's included), and the pixels it stopped at their
// pilot without a proof with the most such a stop can bias a pixel.
struct AdaptiveReferenceRecord {
  static constexpr RecordDoc kSchema{
      "AdaptiveReferenceRecord",
      "the adaptive reference's settings and what it did (config `reference.adaptive`, "
      "docs/config.md \"The adaptive reference\")"};

  int pilot_spp = 0;
  double target_std_error = 0;
  double mean_spp = 0;
  int max_spp = 0;
  // Absent from records before adaptive version 4.
  std::optional<std::int64_t> unproven_stops;
  std::optional<double> stop_bias_bound;

  template <class V>
  static void describe(V& v) {
    using R = AdaptiveReferenceRecord;
    v.field("pilot_spp", &R::pilot_spp, {"", "the pilot's light samples per covered pixel"});
    v.field("target_std_error", &R::target_std_error, {"", "the standard error it stops at"});
    v.field("mean_spp", &R::mean_spp, {"", "light samples per covered pixel, pilot included"});
    v.field("max_spp", &R::max_spp,
            {"",
             "the most samples a pixel took: at most `spp` + `pilot_spp` (before adaptive "
             "version 4 the pilot's samples were part of the estimate, at most `spp`)"});
    v.field("unproven_stops", &R::unproven_stops,
            {"",
             "covered pixels stopped at an agreeing pilot by the window rule, without a "
             "proof; absent from records before adaptive version 4"});
    v.field("stop_bias_bound", &R::stop_bias_bound,
            {"",
             "the most such a stop can bias a pixel, max_p p(1-p)^pilot_spp; 0 when there "
             "is none; absent from records before adaptive version 4"});
  }
};

struct ReferenceRecord {
  static constexpr RecordDoc kSchema{"ReferenceRecord",
                                     "the ray-traced reference the job was measured against"};

  // "embree_stratified_packet16", "embree_stratified_adaptive" or "exact_clipper"
  std::string method;
  // Why a reference asked to be exact is Monte Carlo ("" otherwise; absent
  // from the JSON then).
  std::string exact_fallback;
  int spp = 0;
  std::uint64_t seed = 0;
  std::string embree_isa;     // the ISA that traced it
  std::string embree_config;  // as chosen: option, experiment or environment
  double mean_std_error = 0;
  // Absent from records before reference method version 7.
  std::optional<std::int64_t> estimate_pixels, stopped_pixels;
  std::optional<double> mean_stop_bound;
  std::optional<std::string> penumbra_source;
  double penumbra_mean_std_error = 0;
  double penumbra_rms_std_error = 0;
  std::int64_t penumbra_pixels = 0;  // measured ones only
  std::int64_t attached_shadow_pixels = 0;
  std::int64_t horizon_cut_pixels = 0;  // in no region but `terminator`
  std::string cache_key;
  bool from_cache = false;
  double seconds = 0;
  std::optional<AdaptiveReferenceRecord> adaptive;

  template <class V>
  static void describe(V& v) {
    using R = ReferenceRecord;
    v.field("method", &R::method,
            {"",
             "`embree_stratified_packet16`, `embree_stratified_adaptive`, or `exact_clipper` "
             "(the exact reference, whose `spp` is 0)"});
    v.field("exact_fallback", &R::exact_fallback,
            {"", "why a reference asked to be exact is Monte Carlo", Presence::UnlessEmpty});
    v.field("spp", &R::spp, {"", "light samples per pixel"});
    v.field("seed", &R::seed, {"", "the sampler's seed"});
    v.field("embree_isa", &R::embree_isa, {"", "the ISA that traced it"});
    v.field("embree_config", &R::embree_config,
            {"", "as chosen: option, experiment or environment"});
    v.field("mean_std_error", &R::mean_std_error,
            {"",
             "mean σ over the estimates strictly between 0 and 1 (before reference method "
             "version 7: over every covered pixel, an agreeing pixel's bound counted as its σ)"});
    v.field("estimate_pixels", &R::estimate_pixels,
            {"px",
             "covered pixels whose estimate lies strictly between 0 and 1, each with σ > 0; "
             "absent before reference method version 7"});
    v.field("stopped_pixels", &R::stopped_pixels,
            {"px",
             "covered pixels whose samples all agreed with no proof that none could differ "
             "(σ 0, a stop bound beside it: `images.reference_stop_bound`); absent before "
             "reference method version 7"});
    v.field("mean_stop_bound", &R::mean_stop_bound,
            {"",
             "the mean of their stop bounds, max_p p(1-p)^(n/2) for n agreeing samples: the "
             "most root mean square error such a pixel can hide; absent before reference method "
             "version 7"});
    v.field("penumbra_source", &R::penumbra_source,
            {"",
             "how the penumbra was decided: `exact` (the light partly seen, by the exact "
             "visibility wherever the samples all agreed; the same at any spp) or `sampled` "
             "(the estimates strictly between 0 and 1, for scenes with no exact form: it "
             "misses soft pixels whose samples agreed); absent before reference method "
             "version 7 (`sampled`)"});
    v.field("penumbra_mean_std_error", &R::penumbra_mean_std_error,
            {"", "mean noise over its penumbra: σ, or the stop bound where the samples agreed"});
    v.field("penumbra_rms_std_error", &R::penumbra_rms_std_error,
            {"",
             "sqrt of the mean squared noise over its penumbra (σ, or the stop bound where the "
             "samples agreed): what the noise warning compares with the penumbra RMSE"});
    v.field("penumbra_pixels", &R::penumbra_pixels,
            {"px", "the penumbra's measured pixels: the size of the `penumbra` region"});
    v.field("attached_shadow_pixels", &R::attached_shadow_pixels,
            {"px",
             "pixels facing away from all of the light, where V is 0 for every technique and the "
             "reference"});
    v.field("horizon_cut_pixels", &R::horizon_cut_pixels,
            {"px",
             "pixels whose tangent plane cuts the light, left out of every region but "
             "`terminator` (docs/design.md \"One definition of V\")"});
    v.field("cache_key", &R::cache_key,
            {"",
             "the reference cache's key for it, written also with `--no-cache`; `compare` "
             "compares errors only where it and the settings agree"});
    v.field("from_cache", &R::from_cache, {"", "read from the cache"});
    v.field("seconds", &R::seconds, {"s", "to trace it (or read it)"});
    v.field("adaptive", &R::adaptive, {"", "only for `embree_stratified_adaptive`"});
  }

  nlohmann::json to_json() const;
  static ReferenceRecord from_json(const Fields& f);
};

}  // namespace sb::record
