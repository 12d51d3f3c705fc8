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

namespace sb {

struct SecondReferenceRecord {
  ReferenceRecord reference;
  ImageMetrics visibility;

  nlohmann::json to_json() const;
  static SecondReferenceRecord from_json(const Fields& f);
};

}  // namespace sb
