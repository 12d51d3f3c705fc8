#pragma once
// Parameter documentation generated from the ParamSpecs themselves, so the
// tables in docs/parameters.md (`shadowbench list --markdown`) cannot drift
// from what the config reader accepts.
#include <string>
#include <vector>

#include "core/params.h"

namespace sb {

// | parameter | type | default | accepted | meaning |, one row per spec.
std::string markdown_param_table(const std::vector<ParamSpec>& specs);

}  // namespace sb
