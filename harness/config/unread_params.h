#pragma once
// Parameters a technique declares but never reads. A declared parameter is
// listed by `shadowbench list` and docs/parameters.md, and may be swept; if
// the technique's factory and constructor never read it, a sweep over it
// runs one technique several times under different names, and its docs
// promise an effect that does not exist. Each technique variant is created
// once, right after the config is loaded, on a fresh copy of its Params, and
// the parameters no get_*() read are reported. No GL context is needed: no
// technique's constructor touches GL (plugin/technique.h).
#include <string>
#include <vector>

#include "config/experiment.h"

namespace sb::config {

// The parameters `info.create(params)` does not read, in declaration order.
// Empty when create() throws: the job says why when it runs.
std::vector<std::string> unread_parameters(const plugin::TechniqueInfo& info,
                                           const core::Params& params);

// One warning per technique variant of `e` and parameter it never reads,
// naming the config, the entry, the technique variant and the parameter.
std::vector<std::string> unread_parameter_warnings(const Experiment& e);

}  // namespace sb::config
