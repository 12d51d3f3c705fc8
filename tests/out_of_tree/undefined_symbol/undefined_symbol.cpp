// Registers nothing unless a function, undefined without DEFINE_IT, says so.
#include "plugin/registry.h"

int sb_test_function_nobody_defines();
#ifdef DEFINE_IT
int sb_test_function_nobody_defines() { return 0; }
#endif

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& /*registry*/) { (void)sb_test_function_nobody_defines(); }
