#pragma once
// The plan as JSON: what `shadowbench plan CONFIG --json` prints and `run`
// writes to its run folder as plan.json, so that what a run was told to do
// can be read beside what it recorded. The shape (docs/results.md, "plan.json"):
//   {"plan_version": 1, "config": file, "name": experiment name,
//    "shard_count": N, "counts": {"run": n, "skip": n, "fail": n},
//    "scenes": [{"name", "error", "bad_input", "input_error", "log": [...]}],
//    "jobs": [{"id", "index", "scene", "resolution", "technique", "outcome",
//              "reason", "bad_input", "cost", "shard"}]}
// Jobs in plan order; "scene", "resolution" and "technique" are the variants'
// names; "outcome" is "run", "skip" or "fail".
#include <nlohmann/json.hpp>

#include "config/experiment.h"
#include "plan/plan.h"

namespace sb {

constexpr int kPlanVersion = 1;

nlohmann::json plan_to_json(const Experiment& e, const Plan& plan);

}  // namespace sb
