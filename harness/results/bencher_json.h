#pragma once
// Bencher Metric Format (BMF) JSON (`--bencher-out FILE`), for
// `bencher run --adapter json --file FILE`. One benchmark per ok job, named
// by its job_id, with the measures:
//   latency        frame time in nanoseconds (Bencher's built-in Latency
//                  measure is in ns): value = median, lower_value = p10,
//                  upper_value = p90
//   rmse           visibility RMSE over all pixels
//   penumbra-rmse  visibility RMSE over the reference penumbra
// A non-finite value has no JSON number: that measure is left out.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

nlohmann::json make_bencher_json(const std::vector<record::JobRecord>& records);
void write_bencher_json(const std::string& path, const std::vector<record::JobRecord>& records);

}  // namespace sb::results
