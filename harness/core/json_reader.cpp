#include "core/json_reader.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/bounded_text.h"
#include "core/nearest_names.h"

namespace sb::core {

using json = nlohmann::json;

namespace {

// A value's JSON text. Values may hold bytes that are not UTF-8 (a scene
// spec from a command line): shown as U+FFFD, never thrown.
std::string text_of(const json& v) {
  return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

std::string describe(const json& v) {
  if (v.is_null()) return "null";
  const std::string d = text_of(v);
  return std::string(v.type_name()) + " " + (d.size() > 60 ? bounded_text(d, 57) : d);
}

std::string pointer_token(const std::string& key) {
  std::string out;
  for (const char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

std::string range_bound(double v) {
  json j = v;
  if (v == std::floor(v) && std::fabs(v) < 1e15) j = static_cast<long long>(v);
  return j.dump();
}

void JsonReader::fail(const std::string& pointer, const std::string& problem) const {
  fail_(pointer, problem);
  std::abort();  // Fail must throw
}

const json& JsonReader::object(const json& v, const std::string& pointer,
                               const std::string& what) const {
  if (!v.is_object())
    fail(pointer, "expected " + (what.empty() ? std::string("an object") : what + " (an object)") +
                      ", found " + describe(v));
  return v;
}

const json& JsonReader::member(const json& obj, const std::string& pointer,
                               const std::string& key) const {
  const auto it = object(obj, pointer).find(key);
  if (it == obj.end()) fail(pointer, "missing required key \"" + key + "\" in this object");
  return *it;
}

void JsonReader::only_keys(const json& obj, const std::string& pointer,
                           const std::vector<std::string>& allowed, const std::string& noun) const {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == it.key();
    if (!ok) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      std::string problem = "unknown " + noun + " '" + it.key() + "' (" +
                            (list.empty() ? "expected none" : "expected one of: " + list) + ")";
      if (const std::string near = did_you_mean(it.key(), allowed); !near.empty())
        problem += ";" + near;
      fail(pointer + "/" + pointer_token(it.key()), problem);
    }
  }
}

const json& JsonReader::array(const json& v, const std::string& pointer,
                              const std::string& what) const {
  if (!v.is_array()) fail(pointer, "expected an array of " + what + ", found " + describe(v));
  return v;
}

std::string JsonReader::string(const json& v, const std::string& pointer) const {
  if (!v.is_string()) fail(pointer, "expected a string, found " + describe(v));
  return v.get<std::string>();
}

bool JsonReader::boolean(const json& v, const std::string& pointer) const {
  if (!v.is_boolean()) fail(pointer, "expected true or false, found " + describe(v));
  return v.get<bool>();
}

std::string JsonReader::choice(const json& v, const std::string& pointer,
                               const std::vector<std::string>& choices) const {
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
  if (!v.is_string()) fail(pointer, "expected one of " + list + ", found " + describe(v));
  for (const auto& c : choices)
    if (c == v.get_ref<const std::string&>()) return c;
  fail(pointer, "expected one of " + list + ", found " + text_of(v));
}

std::int64_t JsonReader::integer(const json& v, const std::string& pointer, std::int64_t lo,
                                 std::int64_t hi, bool whole_floats) const {
  const auto out_of_range = [&] {
    fail(pointer, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "], found " + text_of(v));
  };
  if (v.is_number_integer()) {
    if (v.is_number_unsigned() &&
        v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
      out_of_range();
    const auto i = v.get<std::int64_t>();
    if (i < lo || i > hi) out_of_range();
    return i;
  }
  if (whole_floats && v.is_number_float() && v.get<double>() == std::floor(v.get<double>())) {
    const double d = v.get<double>();
    if (!(d >= double(lo) && d <= double(hi))) out_of_range();
    return static_cast<std::int64_t>(d);
  }
  fail(pointer, "expected an integer, found " + describe(v));
}

std::uint64_t JsonReader::unsigned_integer(const json& v, const std::string& pointer) const {
  if (!v.is_number_integer()) fail(pointer, "expected an integer, found " + describe(v));
  if (!v.is_number_unsigned() && v.get<std::int64_t>() < 0)
    fail(pointer, "expected an integer in [0, " +
                      std::to_string(std::numeric_limits<std::uint64_t>::max()) + "], found " +
                      text_of(v));
  return v.get<std::uint64_t>();
}

double JsonReader::number(const json& v, const std::string& pointer, double lo, double hi) const {
  if (!v.is_number()) fail(pointer, "expected a number, found " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(d) || !(d >= lo && d <= hi))
    fail(pointer, "expected a number in [" + range_bound(lo) + ", " + range_bound(hi) +
                      "], found " + text_of(v));
  return d;
}

double JsonReader::record_number(const json& v, const std::string& pointer) const {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  fail(pointer, "expected a number (or \"nan\", \"inf\", \"-inf\"), found " + describe(v));
}

void JsonReader::refuse(const json& v, const std::string& pointer,
                        const std::string& expected) const {
  fail(pointer, "expected " + expected + ", found " + text_of(v));
}

}  // namespace sb::core
