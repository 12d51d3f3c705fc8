#pragma once
// The registry of techniques. Each technique family is a plugin module
// (techniques/<family>/) exporting one C entry point,
//   extern "C" void shadowbench_register_plugin(sb::Registry&);
// that adds its variants, and the providers of any need of its own
// (plugin/needs.h). The harness loads every module in its plugin folder.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/install_layout.h"  // default_plugin_dir(), for callers of load_plugins
#include "core/params.h"
#include "plugin/needs.h"
#include "plugin/plugin_identity.h"
#include "plugin/technique.h"

namespace sb::plugin {

struct TechniqueInfo {
  std::string name;     // unique, used in configs: "shadow_map"
  std::string family;   // the plugin folder: "shadow_map"
  std::string summary;  // one line for `shadowbench list`
  Needs needs;
  std::vector<core::ParamSpec> params;
  std::function<std::unique_ptr<Technique>(const core::Params&)> create;
  // Optional rule across parameters, checked when a config is loaded: returns
  // "" when fine, else {parameter to blame, what is wrong}.
  std::function<std::pair<std::string, std::string>(const core::Params&)> check = nullptr;
  // Optional: a job's cost relative to a hard shadow map's at the same
  // resolution (1 when absent), for balancing shards (plan/shards.h), e.g.
  // accumulation's, which grows with its light samples.
  std::function<double(const core::Params&)> cost_weight = nullptr;
  // Optional: needs only some parameter values have, checked after `needs`
  // for each variant (two_map_bound's gradient shade needs opaque casters,
  // its other shades do not).
  std::function<Needs(const core::Params&)> needs_of_params = nullptr;
  // Frames that depend on the frames before them since prepare(): per-frame
  // sample sequences, temporal accumulation. Frame k after prepare() is then
  // a deterministic function of the inputs of frames 1..k, not of frame k's
  // alone; the timing contract and the measured V treat it so.
  bool temporal = false;
};

// A module load_plugins could not load: its path and the loader's own
// words (dlerror(), the missing entry point, what registering threw).
struct PluginLoadFailure {
  std::string file;
  std::string message;
};

class Registry {
 public:
  void add(TechniqueInfo info);  // throws std::logic_error on duplicates
  const TechniqueInfo* find(const std::string& name) const;
  const std::vector<TechniqueInfo>& all() const { return techniques_; }
  // The module that registered `technique` (load_plugins); nullptr for one
  // added otherwise (a test's own) or unknown.
  const PluginIdentity* plugin_of(const std::string& technique) const;

  // Needs a plugin adds; the harness's own are found by the planner
  // (plan/need_resolution.h). Throws std::logic_error on duplicates.
  void add_provider(NeedProvider provider);
  const NeedProvider* find_provider(const std::string& name) const;
  const std::vector<NeedProvider>& providers() const { return providers_; }

  // Loads every *.so in `dir`; throws std::runtime_error only when `dir` is
  // not a folder. A module that cannot be loaded (a dlopen failure, no entry
  // point, a throw while registering, a technique or need another module
  // registered already) is not fatal: whatever it registered is taken back
  // and it is kept in load_failures(), so that commands not needing it still
  // work. A module already loaded from another folder name is skipped.
  // Returns the count of modules loaded.
  int load_plugins(const std::string& dir);

  // The modules that failed to load, in load order.
  const std::vector<PluginLoadFailure>& load_failures() const { return failures_; }

  // Where plugins were looked for, said with an unknown technique
  // ("$SHADOWBENCH_PLUGIN_PATH is not set: ..."); set by the driver, which
  // knows its folders. "" for none.
  void set_search_hint(std::string hint) { search_hint_ = std::move(hint); }
  const std::string& search_hint() const { return search_hint_; }

 private:
  // Runs a module's entry point; on a throw, takes back what it registered
  // and returns why ("" when it registered fine).
  std::string register_module(const std::string& file, void (*entry)(Registry&));

  std::vector<TechniqueInfo> techniques_;
  std::vector<NeedProvider> providers_;
  std::vector<void*> modules_;  // kept open for the process lifetime
  std::vector<std::string> module_paths_;
  std::map<std::string, std::string> origins_;  // technique (or "need x") -> module
  std::string loading_;                         // the module being registered
  // Module -> its identity, hashed once, when it registers its first technique.
  std::map<std::string, PluginIdentity> identities_;
  std::vector<PluginLoadFailure> failures_;
  std::string search_hint_;
};

}  // namespace sb::plugin

#define SHADOWBENCH_PLUGIN_ENTRY \
  extern "C" __attribute__((visibility("default"))) void shadowbench_register_plugin

// The umbrella of the plugin API: with it, the names a plugin uses stay
// reachable as sb::X (plugin/api_names.h).
#include "plugin/api_names.h"  // IWYU pragma: export
