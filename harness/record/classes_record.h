#pragma once
// record["classes"]: the job's lit / penumbra / umbra classes against the
// reference's (metrics/shadow_classes.h), over the measured geometry pixels
// outside attached shadow, where both could differ. For a technique that
// classifies (two_map_bound) it is its classification's confusion matrix;
// for any technique it says how much penumbra it misses (hard shadows miss
// all of it) and how much it invents (outer-penumbra techniques, blurs).
//
//   "counts": {"lit": [l, p, u], "penumbra": [l, p, u], "umbra": [l, p, u]}
//       keyed by the reference's class; each row the technique's lit,
//       penumbra and umbra pixel counts
//   "penumbra_missed":   reference penumbra pixels the technique calls lit or umbra,
//                        over all reference penumbra pixels (absent when there are none)
//   "penumbra_invented": technique penumbra pixels the reference calls lit or umbra,
//                        over all technique penumbra pixels (absent when there are none)
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "record/fields.h"

namespace sb {

struct ClassesRecord {
  std::array<std::array<std::int64_t, 3>, 3>
      counts{};  // [reference][technique]: lit, penumbra, umbra

  std::optional<double> penumbra_missed() const;
  std::optional<double> penumbra_invented() const;

  nlohmann::json to_json() const;
  static ClassesRecord from_json(const Fields& f);
};

}  // namespace sb
