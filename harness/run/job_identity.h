#pragma once
// What identifies a job, decided without GL, so that the parent process of
// isolated jobs knows it too: the spec hash a rerun compares, and the part
// of the record that needs no rendering (config, scene and technique as
// configured, resolution, backend, host, build).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "plan/plan.h"
#include "record/job_record.h"
#include "reference/settings.h"
#include "run/runner.h"

namespace sb::run {

// The reference's Embree device, resolved once per run: a CPU without the
// ISA is the environment's problem, found before any job runs.
struct EmbreeChoice {
  std::string config;  // as chosen: option, experiment, environment or ""
  std::string isa;     // what it resolves to on this CPU
};
EmbreeChoice choose_embree(const config::Experiment& e, const RunOptions& o);

// A reference's settings as a run hands them to reference::get: the
// config's, with the run's Embree device and the method asked for (the
// first reference's or the second's).
reference::Settings reference_settings(const config::ReferenceConfig& c, const EmbreeChoice& embree,
                                       bool exact);

// Everything that decides a job's numbers, as named fields (the record's
// "spec", docs/results.md), generated from the declarations where each
// setting is described (core::Decides): the scene (config::scene_identity:
// its parameters, a file by the content of what building the scene read,
// `inputs`), the resolution and the technique (config::technique_identity);
// every config block key that decides a number (config::blocks_identity);
// and the parts that are no config key, listed in job_identity.cpp
// (run_parts): the reference's method with its version and the Embree ISA,
// how frames are timed, the backend and the build.
nlohmann::json job_spec(const config::Experiment& e, const RunOptions& o,
                        const EmbreeChoice& embree, const config::SceneVariant& sv,
                        const std::vector<core::InputFile>& inputs, const config::Resolution& res,
                        const config::TechniqueVariant& tv);

// The hash of job_spec(). A rerun into the same folder keeps a finished
// record only when its hash is the same (record/spec_changes.h says why not).
std::string job_spec_hash(const nlohmann::json& spec);

// The record's identity: everything but the built scene, the GL context's
// strings and what the job measures. `sv`, `res` and `tv` must be elements
// of `e`'s own lists (job_index is their place in them); `inputs` are the
// files building `sv` read (core::Scene::inputs). The host is described with the GL
// renderer and version given ("" before any context exists).
record::JobRecord identity_record(const config::Experiment& e, const RunOptions& o,
                                  const EmbreeChoice& embree, const config::SceneVariant& sv,
                                  const std::vector<core::InputFile>& inputs,
                                  const config::Resolution& res, const config::TechniqueVariant& tv,
                                  const std::string& gl_renderer = "",
                                  const std::string& gl_version = "");

// The record's scene.built: what planning `sv` built (`st`).
record::BuiltScene built_scene(const config::SceneVariant& sv, const plan::ScenePlan& st);

// Now, UTC, as records write it: "2026-12-03T11:04:55Z".
std::string now_iso8601();

}  // namespace sb::run
