#include "record/plan_record.h"

#include "record/record_json.h"

namespace sb::record {

void PlanRecord::check(const PlanRecord& p, const Fields& f) {
  if (p.plan_version != kPlanVersion)
    f.fail("plan_version", "is " + std::to_string(p.plan_version) +
                               "; this build reads plan version " + std::to_string(kPlanVersion) +
                               " only");
  if (p.shard_count < 1)
    f.fail("shard_count", "expected at least 1, found " + std::to_string(p.shard_count));
  PlanCounts counted;
  const std::vector<Fields> jobs = f.objects("jobs");
  for (size_t i = 0; i < p.jobs.size(); ++i) {
    const PlannedJobRecord& j = p.jobs[i];
    if (j.index != static_cast<std::int64_t>(i))
      jobs[i].fail("index", "is " + std::to_string(j.index) + " at place " + std::to_string(i) +
                                " of the jobs: the jobs are in plan order");
    if (j.shard < 1 || j.shard > p.shard_count)
      jobs[i].fail("shard", "is " + std::to_string(j.shard) + ", not within 1 to shard_count " +
                                std::to_string(p.shard_count));
    const std::string outcome = jobs[i].choice("outcome", {"run", "skip", "fail"});
    (outcome == "run" ? counted.run : outcome == "skip" ? counted.skip : counted.fail) += 1;
  }
  if (!(counted == p.counts))
    f.fail("counts", "say " + std::to_string(p.counts.run) + " run, " +
                         std::to_string(p.counts.skip) + " skip, " + std::to_string(p.counts.fail) +
                         " fail; the jobs are " + std::to_string(counted.run) + ", " +
                         std::to_string(counted.skip) + " and " + std::to_string(counted.fail));
}

nlohmann::json PlanRecord::to_json() const { return write_record(*this); }

PlanRecord PlanRecord::from_json(const nlohmann::json& j) {
  return read_record<PlanRecord>(Fields(j, ""));
}

namespace {

std::string in_quotes(const std::string& s) { return "\"" + s + "\""; }

std::string job_difference(const PlannedJobRecord& a, const PlannedJobRecord& b) {
  const std::string job = "job " + std::to_string(a.index) + " (" + a.id + ")";
  if (a.id != b.id) return "job " + std::to_string(a.index) + " is " + a.id + ", there " + b.id;
  if (a.outcome != b.outcome || a.reason != b.reason)
    return job + " is planned to " + a.outcome + (a.reason.empty() ? "" : " (" + a.reason + ")") +
           ", there to " + b.outcome + (b.reason.empty() ? "" : " (" + b.reason + ")");
  if (a.shard != b.shard)
    return job + " is in shard " + std::to_string(a.shard) + ", there in shard " +
           std::to_string(b.shard);
  if (!(a == b)) return job + " is planned otherwise (names, cost or input error)";
  return "";
}

}  // namespace

std::string plan_difference(const PlanRecord& a, const PlanRecord& b) {
  if (a.name != b.name)
    return "the experiment is " + in_quotes(a.name) + ", there " + in_quotes(b.name);
  if (a.shard_count != b.shard_count)
    return std::to_string(a.shard_count) + " shards, there " + std::to_string(b.shard_count);
  if (a.jobs.size() != b.jobs.size())
    return std::to_string(a.jobs.size()) + " jobs, there " + std::to_string(b.jobs.size());
  for (size_t i = 0; i < a.jobs.size(); ++i)
    if (std::string d = job_difference(a.jobs[i], b.jobs[i]); !d.empty()) return d;
  if (a.scenes.size() != b.scenes.size())
    return std::to_string(a.scenes.size()) + " scenes, there " + std::to_string(b.scenes.size());
  for (size_t i = 0; i < a.scenes.size(); ++i)
    if (!(a.scenes[i] == b.scenes[i]))
      return "scene " + in_quotes(a.scenes[i].name) + " is planned otherwise (its log or error)";
  return "";
}

}  // namespace sb::record
