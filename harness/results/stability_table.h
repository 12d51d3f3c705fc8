#pragma once
// The stability table (docs/stability.md): technique × case, each cell ok,
// degraded or broken with the figure behind the verdict, from the records
// of a run with a "stability" block. summary.md and the HTML report show it.
#include <optional>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

enum class StabilityVerdict { Ok, Degraded, Broken, Failed, Skipped };
const char* to_string(StabilityVerdict v);  // "ok", "degraded", "broken", "failed", "skipped"

struct StabilityCell {
  StabilityVerdict verdict = StabilityVerdict::Ok;
  // What the verdict rests on: "rmse 0.0213; flicker 0.0011 (reference
  // 0.0009)", "rmse 0.21 > 0.1", "stiff: exponent 3.2", "1536 NaN/Inf".
  std::string figure;
};

// The verdict on one record:
//  - broken: V was NaN/Inf or outside [0, 1] (the visibility check failed it);
//  - failed: it failed otherwise (the reason); skipped: it did not run;
//  - degraded: RMSE over stability.max_rmse; a mean flicker, or a share of
//    popping pixels (|ΔV| > 0.05), over flicker_factor × the reference's +
//    kFlickerFloor; or a stiff parameter;
//  - ok otherwise.
StabilityCell stability_cell(const record::JobRecord& r);

struct StabilityTable {
  std::vector<std::string> cases;       // scene variants (with "@ WxH" when a run has several)
  std::vector<std::string> techniques;  // technique variants, in the run's order
  // cells[t][c]: the record of technique t in case c, if the run has one.
  std::vector<std::vector<const record::JobRecord*>> cells;
};

// nullopt when no record carries stability figures (a run without the block).
std::optional<StabilityTable> stability_table(const std::vector<record::JobRecord>& records);

// The table as a Markdown section ("" without one).
std::string stability_markdown(const std::vector<record::JobRecord>& records);

}  // namespace sb::results
