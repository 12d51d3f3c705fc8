#pragma once
// The plan as JSON: what `shadowbench plan CONFIG --json` prints and `run`
// writes to its run folder as plan.json, so that what a run was told to do
// can be read beside what it recorded. Its shape is record/plan_record.h's
// PlanRecord (docs/results.md, "The plan"): per scene variant its log and
// error, per job in plan order its id, index, variant names, outcome
// ("run", "skip" or "fail"), reason, cost and shard.
#include <nlohmann/json.hpp>
#include <string>

#include "config/experiment.h"
#include "plan/plan.h"
#include "record/plan_record.h"

namespace sb::plan {

record::PlanRecord plan_record(const config::Experiment& e, const Plan& plan);
nlohmann::json plan_to_json(const config::Experiment& e, const Plan& plan);

// A plan.json read back. Throws InputError naming the file, the line and
// column and the JSON pointer of what is wrong (a file of another
// plan_version is refused so).
record::PlanRecord read_plan_file(const std::string& path);
// The same, of a plan.json's text read by the caller (`path` names it in errors).
record::PlanRecord read_plan_text(const std::string& text, const std::string& path);

}  // namespace sb::plan
