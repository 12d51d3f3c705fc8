#include "plan/plan_json.h"

namespace sb {

using json = nlohmann::json;

json plan_to_json(const Experiment& e, const Plan& plan) {
  json scenes = json::array();
  for (size_t s = 0; s < plan.scenes.size(); ++s) {
    const ScenePlan& sp = plan.scenes[s];
    scenes.push_back({{"name", e.scenes[s].name},
                      {"error", sp.error},
                      {"bad_input", sp.bad_input},
                      {"input_error", sp.input_error},
                      {"log", sp.log}});
  }
  json jobs = json::array();
  for (const PlannedJob& j : plan.jobs)
    jobs.push_back({{"id", j.id},
                    {"index", j.index},
                    {"scene", e.scenes[j.scene].name},
                    {"resolution", e.resolutions[j.resolution].label()},
                    {"technique", e.techniques[j.technique].name},
                    {"outcome", to_string(j.outcome.status)},
                    {"reason", j.outcome.reason},
                    {"bad_input", j.outcome.bad_input},
                    {"cost", j.cost},
                    {"shard", j.shard}});
  return {{"plan_version", kPlanVersion},
          {"config", e.file},
          {"name", e.name},
          {"shard_count", plan.shard_count},
          {"counts",
           {{"run", plan.count(JobOutcome::Status::Run)},
            {"skip", plan.count(JobOutcome::Status::Skip)},
            {"fail", plan.count(JobOutcome::Status::Fail)}}},
          {"scenes", std::move(scenes)},
          {"jobs", std::move(jobs)}};
}

}  // namespace sb
