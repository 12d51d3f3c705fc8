#pragma once
// A "techniques" entry (and frames.control): a name, or {"name", "params",
// "label", "own_map_size"} whose list-valued params sweep, as its variants.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/config_reader.h"
#include "config/experiment.h"

namespace sb::config {

// `may_be_unavailable`: a name no plugin registered, while some plugin failed
// to load, gives stand-in variants whose jobs fail (config/unknown_technique.h).
std::vector<TechniqueVariant> technique_variants(const ConfigReader& r,
                                                 const plugin::Registry& registry,
                                                 const nlohmann::json& given_entry,
                                                 const std::string& pointer,
                                                 const std::string& file, bool may_be_unavailable);

}  // namespace sb::config
