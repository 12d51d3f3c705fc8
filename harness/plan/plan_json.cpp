#include "plan/plan_json.h"

#include "config/json_file.h"
#include "core/error.h"
#include "core/json_positions.h"

namespace sb::plan {

using config::Experiment;
using config::JsonLimits;
using config::parse_json_text;
using config::read_input_file;
using core::InputError;
using core::JsonPositions;
using record::PlanRecord;
using record::RecordError;

PlanRecord plan_record(const Experiment& e, const Plan& plan) {
  PlanRecord p;
  p.config = e.file;
  p.name = e.name;
  p.shard_count = plan.shard_count;
  p.counts = {static_cast<std::int64_t>(plan.count(JobOutcome::Status::Run)),
              static_cast<std::int64_t>(plan.count(JobOutcome::Status::Skip)),
              static_cast<std::int64_t>(plan.count(JobOutcome::Status::Fail))};
  for (size_t s = 0; s < plan.scenes.size(); ++s) {
    const ScenePlan& sp = plan.scenes[s];
    p.scenes.push_back({e.scenes[s].name, sp.error, sp.bad_input, sp.input_error, sp.log});
  }
  for (const PlannedJob& j : plan.jobs)
    p.jobs.push_back({j.id, static_cast<std::int64_t>(j.index), e.scenes[j.scene].name,
                      e.resolutions[j.resolution].label(), e.techniques[j.technique].name,
                      to_string(j.outcome.status), j.outcome.reason, j.outcome.bad_input, j.cost,
                      j.shard});
  return p;
}

nlohmann::json plan_to_json(const Experiment& e, const Plan& plan) {
  return plan_record(e, plan).to_json();
}

PlanRecord read_plan_file(const std::string& path) {
  return read_plan_text(read_input_file(path, JsonLimits{}.max_bytes, "plan"), path);
}

PlanRecord read_plan_text(const std::string& text, const std::string& path) {
  JsonPositions positions;
  const nlohmann::json j = parse_json_text(text, path, {}, 0, &positions);
  try {
    return PlanRecord::from_json(j);
  } catch (const RecordError& e) {
    throw InputError(path, e.pointer(), e.problem(), positions.find(e.pointer()));
  }
}

}  // namespace sb::plan
