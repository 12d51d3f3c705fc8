#pragma once
// record["reference"]: the ray-traced reference the job was measured
// against (docs/results.md, "reference").
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "record/fields.h"

namespace sb {

struct ReferenceRecord {
  std::string method;  // "embree_stratified_packet16", or "exact_clipper"
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

  nlohmann::json to_json() const;
  static ReferenceRecord from_json(const Fields& f);
};

}  // namespace sb
