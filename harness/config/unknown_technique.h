#pragma once
// What to say about a technique name no loaded plugin registered: the
// nearest registered names, the plugins that failed to load (the name may
// have been one of theirs) and where plugins were looked for.
#include <string>

#include "plugin/registry.h"

namespace sb::config {

struct UnknownTechnique {
  // unknown technique "my_pcf" (plugin /p/my_pcf.so failed to load: <why>);
  // or (registered: ...) when every plugin loaded, then the registry's
  // search hint on a line of its own; and "did you mean" either way, for
  // typos only: a name that extends a loaded one (pcss_stochastic) is a
  // plugin's that was not loaded, not pcss mistyped.
  std::string message;
  // Some module failed to load, so the name may be its: a job naming it
  // fails with `message` (the run goes on) instead of the config being wrong.
  bool plugin_failed = false;
};

// `config_file`, when given, is where the name was read: a plugin built as
// `shadowbench new-technique NAME` writes it, in build/NAME.so beside the
// config, is named with the folder to add to $SHADOWBENCH_PLUGIN_PATH.
// Not when a plugin failed to load: that failure is the likelier cause.
UnknownTechnique unknown_technique(const std::string& name, const plugin::Registry& registry,
                                   const std::string& config_file = "");

}  // namespace sb::config
