#pragma once
// The config's JSON reader: core/json_reader.h's checks, each failing with an
// InputError that names the file and the pointer (load_experiment adds the
// line and column, core/json_positions.h), and the checks only a config
// needs (a label, a coordinate, a positive size).
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_reader.h"

namespace sb::config {

class ConfigReader : public core::JsonReader {
 public:
  explicit ConfigReader(std::string file);
  // An integer in [lo, hi]; 2.0 is refused (unlike a technique parameter).
  int integer(const nlohmann::json& v, const std::string& pointer, long long lo,
              long long hi) const {
    return static_cast<int>(core::JsonReader::integer(v, pointer, lo, hi));
  }
  // A label names variants in tables and charts: short, printable.
  std::string label(const nlohmann::json& v, const std::string& pointer) const;
  glm::vec3 vec3(const nlohmann::json& v, const std::string& pointer) const;
  // A point or direction: finite as a float, and within what can be traced.
  glm::vec3 coordinates(const nlohmann::json& v, const std::string& pointer) const;
  float positive(const nlohmann::json& v, const std::string& pointer, bool allow_zero) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace sb::config
