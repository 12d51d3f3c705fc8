#pragma once
// Which reference a Settings asks for, and on which Embree device: what
// computing, caching and identifying a reference all go by.
#include <string>

#include "reference/embree_isa.h"
#include "reference/reference.h"

namespace sb::reference::detail {

// Result::method of a reference computed with `s` (when the exact
// reference is asked for, the scene is one it can do).
inline const char* method_of(const Settings& s) {
  return s.exact ? kExactMethod : s.adaptive ? kAdaptiveMethod : kStratifiedMethod;
}

// The settings' device config, or the environment's when they leave it empty.
inline std::string embree_config_of(const Settings& s) {
  return s.embree_config.empty() ? default_embree_config() : s.embree_config;
}

}  // namespace sb::reference::detail
