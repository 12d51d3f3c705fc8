// A module as one built against an older plugin API looks to this build: it
// names a shadowbench function by a mangled name this build does not define
// (as every module built before API version 4 names sb::Registry::add, now
// sb::plugin::Registry::add). dlopen fails with "undefined symbol:
// _ZN2sb..."; the driver must say to rebuild it. For the load-failure tests
// only.
#include "plugin/registry.h"

namespace sb {
int a_function_of_an_older_api();  // declared, never defined: what this build lacks
}  // namespace sb

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& /*registry*/) {
  (void)sb::a_function_of_an_older_api();
}
