#include "plan/plan.h"

#include <algorithm>
#include <string>

#include "core/bounded_text.h"
#include "core/error.h"
#include "core/names.h"
#include "plan/shards.h"
#include "scenes/receiver_inference.h"

namespace sb::plan {

using config::build_scene;
using config::Experiment;
using config::SceneVariant;
using core::InputError;
using core::job_id;
using core::Scene;
using plugin::DerivedData;
using plugin::TechniqueInfo;

namespace {

// The techniques as the needs see them: a variant whose needs depend on its
// parameters is a copy of its technique with those needs added (kept in
// `copies`).
std::vector<const TechniqueInfo*> technique_infos(const Experiment& e,
                                                  std::vector<TechniqueInfo>& copies) {
  copies.reserve(e.techniques.size());
  std::vector<const TechniqueInfo*> infos;
  for (const auto& tv : e.techniques) {
    infos.push_back(tv.info);
    if (tv.info->needs_of_params == nullptr) continue;
    TechniqueInfo& copy = copies.emplace_back(*tv.info);
    for (auto& n : tv.info->needs_of_params(tv.params).names) copy.needs.names.push_back(n);
    infos.back() = &copy;
  }
  return infos;
}

// Runs `build`; what it throws is recorded in `p` (a scene's bad input, or
// any other failure), never thrown on.
template <class Build>
void recording_failure(ScenePlan& p, Build build) {
  try {
    build();
  } catch (const InputError& ex) {
    p.input_error = core::bounded_text(ex.what(), core::kMessageChars);
    p.error = "bad scene input: " + p.input_error;
    p.bad_input = true;
  } catch (const std::exception& ex) {
    p.error = "building the scene failed: " + core::bounded_text(ex.what(), core::kMessageChars);
  }
}

}  // namespace

ScenePlan plan_scene(const Experiment& e, const SceneVariant& sv, Derive derive) {
  ScenePlan p;
  p.variant = &sv;
  std::vector<TechniqueInfo> copies;
  const std::vector<const TechniqueInfo*> infos = technique_infos(e, copies);
  recording_failure(p, [&] {
    p.scene = build_scene(sv, e.file);
    if (sv.infer_receivers) p.inferred_receivers = infer_receivers(p.scene);
    if (!p.inferred_receivers.empty()) {
      // The first few by name: a file of 200,000 instanced quads would
      // otherwise print a line of 200,000 names (the records keep them all).
      constexpr size_t kNamed = 8;
      const auto& all = p.inferred_receivers;
      std::string names;
      for (size_t i = 0; i < std::min(all.size(), kNamed); ++i)
        names += (names.empty() ? "" : ", ") + core::quoted_text(all[i]);
      if (all.size() > kNamed)
        names += " and " + std::to_string(all.size() - kNamed) + " more (" +
                 std::to_string(all.size()) + " meshes)";
      p.log.push_back("inferred receivers (planar, can shadow nothing): " + names);
    }
    ResolvedNeeds needs = resolve_needs(p.scene, infos, e.registry, derive);
    p.derived = std::move(needs.data);
    p.uploads = std::move(needs.uploads);
    p.skip_reason = std::move(needs.skip_reason);
    p.needs = std::move(needs.needs);
    for (auto& l : needs.log) p.log.push_back(std::move(l));
    p.derived_for = derive;
    p.deferred_log = needs.deferred;
  });
  return p;
}

void derive_run_needs(const Experiment& e, ScenePlan& p) {
  if (!p.error.empty() || p.derived_for == Derive::All) return;
  std::vector<TechniqueInfo> copies;
  const std::vector<const TechniqueInfo*> infos = technique_infos(e, copies);
  recording_failure(p, [&] {
    ResolvedNeeds needs = resolve_needs(p.scene, infos, e.registry, Derive::All, &p.derived);
    p.derived = std::move(needs.data);
    p.uploads = std::move(needs.uploads);
    p.skip_reason = std::move(needs.skip_reason);
    p.needs = std::move(needs.needs);
    p.log.resize(p.log.size() - p.deferred_log);
    for (auto& l : needs.log) p.log.push_back(std::move(l));
    p.derived_for = Derive::All;
    p.deferred_log = 0;
  });
}

size_t scene_bytes(const Scene& scene) {
  size_t bytes = 0;
  for (const core::Mesh& m : scene.meshes)
    bytes += m.positions.size() * sizeof(m.positions[0]) + m.normals.size() * sizeof(m.normals[0]) +
             m.uvs.size() * sizeof(m.uvs[0]) + m.indices.size() * sizeof(m.indices[0]);
  for (const core::TextureImage& t : scene.textures) bytes += t.rgba.size();
  return bytes;
}

void drop_scene_data(ScenePlan& p) {
  std::vector<core::InputFile> inputs = std::move(p.scene.inputs);
  p.scene = Scene{};
  p.scene.inputs = std::move(inputs);
  p.derived = DerivedData{};
  p.kept = false;
}

const char* to_string(JobOutcome::Status status) {
  switch (status) {
    case JobOutcome::Status::Run:
      return "run";
    case JobOutcome::Status::Skip:
      return "skip";
    case JobOutcome::Status::Fail:
      return "fail";
  }
  return "?";
}

JobOutcome decide_job(const Experiment& e, const ScenePlan& scene, size_t technique) {
  JobOutcome o;
  if (!e.techniques[technique].unavailable.empty()) {  // its plugin failed to load
    o.status = JobOutcome::Status::Fail;
    o.reason = e.techniques[technique].unavailable;
  } else if (!scene.error.empty()) {
    o.status = JobOutcome::Status::Fail;
    o.reason = scene.error;
    o.bad_input = scene.bad_input;
    o.input_error = scene.input_error;
  } else if (!scene.skip_reason[technique].empty()) {
    o.status = JobOutcome::Status::Skip;
    o.reason = scene.skip_reason[technique];
  }
  return o;
}

std::string outcome_mismatch(const JobOutcome& planned, const JobOutcome& decided) {
  if (planned == decided) return "";
  const auto say = [](const JobOutcome& o) {
    std::string s = to_string(o.status);
    if (!o.reason.empty()) s += " (" + o.reason + ")";
    return s;
  };
  return "internal error: the plan says " + say(planned) + ", but the scene built to run it says " +
         say(decided) + "; the job was not run either way";
}

size_t Plan::count(PlannedJob::Status s) const {
  size_t n = 0;
  for (const auto& j : jobs) n += j.outcome.status == s ? 1 : 0;
  return n;
}

Plan make_plan(const Experiment& e, int shard_count, size_t keep_bytes) {
  Plan plan;
  size_t kept_bytes = 0;
  for (size_t s = 0; s < e.scenes.size(); ++s) {
    ScenePlan sp = plan_scene(e, e.scenes[s], Derive::Decide);
    for (size_t r = 0; r < e.resolutions.size(); ++r)
      for (size_t t = 0; t < e.techniques.size(); ++t) {
        PlannedJob j;
        j.id = job_id(e.scenes[s].name, e.resolutions[r].label(), e.techniques[t].name);
        j.index = plan.jobs.size();
        j.scene = s;
        j.resolution = r;
        j.technique = t;
        j.cost = job_cost(e, r, t);
        j.outcome = decide_job(e, sp, t);
        plan.jobs.push_back(std::move(j));
      }
    // A sweep of big scenes must not stay in memory: the builds over the
    // budget are dropped, and the run builds those scenes again.
    const size_t bytes = scene_bytes(sp.scene);
    if (keep_bytes > 0 && (e.scenes.size() == 1 || kept_bytes + bytes <= keep_bytes)) {
      sp.kept = true;
      kept_bytes += bytes;
    } else {
      drop_scene_data(sp);
    }
    plan.scenes.push_back(std::move(sp));
  }
  assign_shards(plan, shard_count);
  return plan;
}

std::string describe_plan(const Experiment& e, const Plan& plan) {
  std::string out = e.file + ": " + std::to_string(plan.jobs.size()) +
                    " jobs: " + std::to_string(plan.count(PlannedJob::Status::Run)) + " to run, " +
                    std::to_string(plan.count(PlannedJob::Status::Skip)) + " skipped, " +
                    std::to_string(plan.count(PlannedJob::Status::Fail)) + " failing\n";
  for (size_t s = 0; s < plan.scenes.size(); ++s) {
    const ScenePlan& sp = plan.scenes[s];
    out += "scene " + core::bounded_text(e.scenes[s].name) + "\n";
    if (!sp.error.empty()) out += "  error: " + sp.error + "\n";
    for (const auto& l : sp.log) out += "  " + l + "\n";
    for (const auto& j : plan.jobs) {
      if (j.scene != s) continue;
      std::string status = to_string(j.outcome.status);
      status.resize(5, ' ');
      out += "  " + status + e.resolutions[j.resolution].label() + "  " +
             core::bounded_text(e.techniques[j.technique].name);
      if (!j.outcome.reason.empty()) out += "  (" + j.outcome.reason + ")";
      out += "\n";
    }
  }
  return out;
}

}  // namespace sb::plan
