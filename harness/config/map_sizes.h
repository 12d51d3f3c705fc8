#pragma once
// Unequal shadow-map sizes among the techniques an experiment compares. A
// technique rendering a 1024² map beside others at 2048² does a quarter of
// their texel work and resolves a quarter of their detail: the time and
// error axes flatter it. Which parameters are map sizes is declared with
// the parameter (ParamSpec::map_size); a swept size compares sizes on
// purpose and is left out, as is an entry marked "own_map_size": true.
#include <string>
#include <vector>

#include "config/experiment.h"

namespace sb::config {

// One warning per technique variant whose map size differs from the size
// most of the others use (the largest on a tie), naming the config, the
// JSON pointer of the size (or of the entry, for a default), both sizes and
// a variant of the common size. Empty when every size agrees.
std::vector<std::string> unequal_map_size_warnings(const Experiment& e);

}  // namespace sb::config
