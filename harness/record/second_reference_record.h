#pragma once
// record["second_reference"]: the job's visibility measured against a second
// reference of the other method (config reference.second_method), over the
// same regions as record["metrics"], so that the two errors can be set side
// by side: against an exact and a Monte Carlo reference, their difference is
// the Monte Carlo reference's noise (docs/results.md, "Two references").
#include <nlohmann/json.hpp>

#include "record/fields.h"
#include "record/metrics_record.h"
#include "record/reference_record.h"

namespace sb::record {

struct SecondReferenceRecord {
  static constexpr RecordDoc kSchema{
      "SecondReferenceRecord",
      "the job's visibility measured against a reference of the other method "
      "(config `reference.second_method`, \"Two references\" above)"};

  ReferenceRecord reference;
  ImageMetrics visibility;

  template <class V>
  static void describe(V& v) {
    v.field("reference", &SecondReferenceRecord::reference,
            {"", "the second reference; its `penumbra_pixels` are its own soft pixels"});
    v.field("visibility", &SecondReferenceRecord::visibility,
            {"", "the visibility buffer's error against it, over the first reference's regions"});
  }

  nlohmann::json to_json() const;
  static SecondReferenceRecord from_json(const Fields& f);
};

}  // namespace sb::record
