#pragma once
// A "resolutions" entry: [width, height] or "WIDTHxHEIGHT".
#include <nlohmann/json.hpp>
#include <string>

#include "config/config_reader.h"
#include "config/experiment.h"

namespace sb::config {

Resolution parse_resolution(const ConfigReader& r, const nlohmann::json& v,
                            const std::string& pointer);

}  // namespace sb::config
