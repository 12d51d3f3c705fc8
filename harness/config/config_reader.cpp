#include "config/config_reader.h"

#include <cmath>

#include "core/error.h"
#include "core/scene_setup_check.h"

namespace sb {

using json = nlohmann::json;

std::string describe(const json& v) {
  std::string d = v.dump();
  if (d.size() > 60) d = d.substr(0, 57) + "...";
  return std::string(v.type_name()) + " " + d;
}

void ConfigReader::fail(const std::string& pointer, const std::string& what) const {
  throw InputError(file_, pointer.empty() ? "/" : pointer, what);
}
const json& ConfigReader::object(const json& v, const std::string& pointer,
                                 const std::string& what) const {
  if (!v.is_object()) fail(pointer, "expected " + what + " (an object), found " + describe(v));
  return v;
}
void ConfigReader::only_keys(const json& obj, const std::string& pointer,
                             const std::vector<std::string>& allowed) const {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == it.key();
    if (!ok) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(pointer + "/" + it.key(),
           "unknown key '" + it.key() + "' (expected one of: " + list + ")");
    }
  }
}
int ConfigReader::integer(const json& v, const std::string& pointer, long long lo,
                          long long hi) const {
  if (!v.is_number_integer()) fail(pointer, "expected an integer, found " + describe(v));
  const auto i = v.get<long long>();
  if (i < lo || i > hi)
    fail(pointer, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "], found " + v.dump());
  return static_cast<int>(i);
}
std::string ConfigReader::string(const json& v, const std::string& pointer) const {
  if (!v.is_string()) fail(pointer, "expected a string, found " + describe(v));
  return v.get<std::string>();
}
std::string ConfigReader::label(const json& v, const std::string& pointer) const {
  std::string s = string(v, pointer);
  if (s.empty() || s.size() > 200)
    fail(pointer, "expected a label of 1 to 200 bytes, found " + std::to_string(s.size()));
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      fail(pointer, "expected a label without control characters, found " + describe(v));
  return s;
}
double ConfigReader::number(const json& v, const std::string& pointer, double lo, double hi) const {
  if (!v.is_number()) fail(pointer, "expected a number, found " + describe(v));
  const double d = v.get<double>();
  if (!(d >= lo && d <= hi))
    fail(pointer, "expected a number in [" + json(lo).dump() + ", " + json(hi).dump() +
                      "], found " + v.dump());
  return d;
}
bool ConfigReader::boolean(const json& v, const std::string& pointer) const {
  if (!v.is_boolean()) fail(pointer, "expected true or false, found " + describe(v));
  return v.get<bool>();
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

}  // namespace sb
