#pragma once
// Resolves the techniques' needs (plugin/needs.h) for one scene: finds each
// need's provider (a plugin's, else the harness's, scenes/need_providers.h),
// computes what was asked for and nothing else, in dependency order, and
// decides which techniques the scene cannot serve.
#include <cstddef>
#include <string>
#include <vector>

#include "core/scene.h"
#include "plugin/registry.h"

namespace sb::plan {

enum class Derive {
  Decide,  // only what skip decisions need (Plan needs); for plan and validate
  All,     // also the Run needs of the techniques that will run; for run
};

struct ResolvedNeeds {
  plugin::DerivedData data;
  std::vector<std::string> skip_reason;  // per technique; "" = runs
  // Per technique: its needs and those they require, dependencies first
  // (empty when one has no provider). What the harness holds for it, and
  // charges it (technique.gpu_bytes).
  std::vector<std::vector<std::string>> needs;
  // GPU stages for the running techniques' needs, in dependency order; the
  // runner calls each once the scene is on the GPU.
  std::vector<const plugin::NeedProvider*> uploads;
  std::vector<std::string> log;  // one line per datum derived or deferred
  size_t deferred = 0;           // of log's last lines, the Run needs left for the run
};

// The provider of `name`: the harness's, else `plugins`' (may be null).
// Throws std::logic_error when a plugin provides a need the harness has.
const plugin::NeedProvider* find_need_provider(const std::string& name,
                                               const plugin::Registry* plugins);

// `decided`, when given, is the data of a Derive::Decide resolution of the
// same scene and techniques: its Plan needs are taken from it, not derived
// again, and the log holds only what this call derives (the run completing
// the plan's build of a scene, plan::derive_run_needs).
ResolvedNeeds resolve_needs(const core::Scene& scene,
                            const std::vector<const plugin::TechniqueInfo*>& techniques,
                            const plugin::Registry* plugins, Derive derive,
                            const plugin::DerivedData* decided = nullptr);

}  // namespace sb::plan
