#include "config/config_reader.h"

#include <cmath>

#include "core/error.h"
#include "core/scene_setup_check.h"

namespace sb::config {

using core::describe;
using core::InputError;
using core::kLargestCoordinate;

using json = nlohmann::json;

ConfigReader::ConfigReader(std::string file)
    : JsonReader([file](const std::string& pointer, const std::string& problem) {
        throw InputError(file, pointer.empty() ? "/" : pointer, problem);
      }),
      file_(std::move(file)) {}

std::string ConfigReader::label(const json& v, const std::string& pointer) const {
  std::string s = string(v, pointer);
  if (s.empty() || s.size() > 200)
    fail(pointer, "expected a label of 1 to 200 bytes, found " + std::to_string(s.size()));
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      fail(pointer, "expected a label without control characters, found " + describe(v));
  return s;
}
glm::vec3 ConfigReader::vec3(const json& v, const std::string& pointer) const {
  if (!v.is_array() || v.size() != 3)
    fail(pointer, "expected an array of 3 numbers, found " + describe(v));
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[size_t(i)].is_number())
      fail(pointer + "/" + std::to_string(i), "expected a number, found " + describe(v[size_t(i)]));
    out[i] = v[size_t(i)].get<float>();
  }
  return out;
}
glm::vec3 ConfigReader::coordinates(const json& v, const std::string& pointer) const {
  const glm::vec3 out = vec3(v, pointer);
  for (int i = 0; i < 3; ++i)
    if (!(std::fabs(out[i]) <= kLargestCoordinate))
      fail(pointer + "/" + std::to_string(i),
           "expected a coordinate within ±1e15, found " + describe(v[size_t(i)]));
  return out;
}
float ConfigReader::positive(const json& v, const std::string& pointer, bool allow_zero) const {
  if (!v.is_number()) fail(pointer, "expected a number, found " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(static_cast<float>(d)))
    fail(pointer, "expected a number within float range, found " + v.dump());
  if (allow_zero ? d < 0.0 : d <= 0.0)
    fail(pointer, std::string("expected a ") + (allow_zero ? "non-negative" : "positive") +
                      " number, found " + v.dump());
  return static_cast<float>(d);
}

}  // namespace sb::config
