#pragma once
// The built plugins, loaded once per test executable.
#include "plugin/registry.h"

namespace sb::test {

inline const plugin::Registry& registry() {
  static const plugin::Registry r = [] {
    plugin::Registry reg;
    reg.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    return reg;
  }();
  return r;
}

}  // namespace sb::test
