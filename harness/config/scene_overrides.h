#pragma once
// A scene entry's "light" and "camera" overrides: checked when the config is
// read (each value, and what the overrides alone can tell about the light and
// the camera), applied when the scene is built (apply_overrides,
// config/experiment.h).
#include <nlohmann/json.hpp>
#include <string>

#include "config/config_reader.h"

namespace sb::config {

void check_light(const ConfigReader& r, const nlohmann::json& light, const std::string& pointer);
void check_camera(const ConfigReader& r, const nlohmann::json& camera, const std::string& pointer);

}  // namespace sb::config
