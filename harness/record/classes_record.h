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

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

struct ClassesRecord {
  static constexpr RecordDoc kSchema{
      "ClassesRecord",
      "the job's lit / penumbra / umbra classes against the reference's, over the measured "
      "geometry pixels outside attached shadow (the job's: V ≤ 1e-6 umbra, V ≥ 1 − 1e-6 lit, "
      "the rest penumbra; the reference's: the `penumbra` region, the rest lit or umbra); for "
      "`two_map_bound` its classification's confusion matrix"};

  std::array<std::array<std::int64_t, 3>, 3>
      counts{};  // [reference][technique]: lit, penumbra, umbra

  std::optional<double> penumbra_missed() const;
  std::optional<double> penumbra_invented() const;

  template <class V>
  static void describe(V& v) {
    using C = ClassesRecord;
    v.custom(
        "counts", "object of class → [integer × 3]",
        {"px",
         "`lit`, `penumbra`, `umbra`, keyed by the reference's class: each "
         "`[lit, penumbra, umbra]`, the job's own classes of those pixels"},
        [](const C& c) { return std::optional(c.counts_json()); },
        [](C& c, const Fields& f) { c.read_counts(f); });
    v.custom(
        "penumbra_missed", "number",
        {"",
         "the reference's penumbra pixels the job calls lit or umbra, over all of them "
         "(a hard shadow misses all); absent when there are none",
         Presence::WhenSet},
        [](const C& c) { return as_json(c.penumbra_missed()); }, [](C&, const Fields&) {});
    v.custom(
        "penumbra_invented", "number",
        {"",
         "the job's penumbra pixels the reference calls lit or umbra, over all of them; "
         "absent when there are none",
         Presence::WhenSet},
        [](const C& c) { return as_json(c.penumbra_invented()); }, [](C&, const Fields&) {});
  }
  nlohmann::json counts_json() const;
  void read_counts(const Fields& f);
  static std::optional<nlohmann::json> as_json(std::optional<double> v) {
    return v ? std::optional<nlohmann::json>(*v) : std::nullopt;
  }

  nlohmann::json to_json() const;
  static ClassesRecord from_json(const Fields& f);
};

}  // namespace sb::record
