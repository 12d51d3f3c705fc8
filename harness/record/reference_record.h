#pragma once
// record["reference"]: the ray-traced reference the job was measured
// against (docs/results.md, "reference").
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "record/fields.h"

namespace sb {

// record["reference"]["adaptive"], only for the adaptive reference
// (reference.adaptive): its settings, the light samples it took per
// covered pixel (the pilot's included), and the pixels it stopped at their
// pilot without a proof with the most such a stop can bias a pixel.
struct AdaptiveReferenceRecord {
  int pilot_spp = 0;
  double target_std_error = 0;
  double mean_spp = 0;
  int max_spp = 0;
  // Absent from records before adaptive version 4.
  std::optional<std::int64_t> unproven_stops;
  std::optional<double> stop_bias_bound;
};

struct ReferenceRecord {
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
  double penumbra_mean_std_error = 0;
  double penumbra_rms_std_error = 0;
  std::int64_t penumbra_pixels = 0;  // measured ones only
  std::int64_t attached_shadow_pixels = 0;
  std::int64_t horizon_cut_pixels = 0;  // left out of every metric
  std::string cache_key;
  bool from_cache = false;
  double seconds = 0;
  std::optional<AdaptiveReferenceRecord> adaptive;

  nlohmann::json to_json() const;
  static ReferenceRecord from_json(const Fields& f);
};

}  // namespace sb
