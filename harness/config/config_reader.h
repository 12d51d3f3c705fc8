#pragma once
// Reading a config's JSON value by value, each named by its JSON pointer: the
// checks every part of an experiment file shares (an object with known keys,
// an integer in a range, a label, a coordinate...), each failing with an
// InputError that names the file, the pointer, what was expected and what was
// found. load_experiment adds the line and column (core/json_positions.h).
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sb {

// "number 3.5", "string \"abc\"": a found value's type and text, cut at 60 bytes.
std::string describe(const nlohmann::json& v);

class ConfigReader {
 public:
  explicit ConfigReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const;
  const nlohmann::json& object(const nlohmann::json& v, const std::string& pointer,
                               const std::string& what) const;
  void only_keys(const nlohmann::json& obj, const std::string& pointer,
                 const std::vector<std::string>& allowed) const;
  int integer(const nlohmann::json& v, const std::string& pointer, long long lo,
              long long hi) const;
  std::string string(const nlohmann::json& v, const std::string& pointer) const;
  // A label names variants in tables and charts: short, printable.
  std::string label(const nlohmann::json& v, const std::string& pointer) const;
  double number(const nlohmann::json& v, const std::string& pointer, double lo, double hi) const;
  bool boolean(const nlohmann::json& v, const std::string& pointer) const;
  glm::vec3 vec3(const nlohmann::json& v, const std::string& pointer) const;
  // A point or direction: finite as a float, and within what can be traced.
  glm::vec3 coordinates(const nlohmann::json& v, const std::string& pointer) const;
  float positive(const nlohmann::json& v, const std::string& pointer, bool allow_zero) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace sb
