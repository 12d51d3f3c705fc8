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
  // search hint on a line of its own; and "did you mean" either way.
  std::string message;
  // Some module failed to load, so the name may be its: a job naming it
  // fails with `message` (the run goes on) instead of the config being wrong.
  bool plugin_failed = false;
};

UnknownTechnique unknown_technique(const std::string& name, const plugin::Registry& registry);

}  // namespace sb::config
