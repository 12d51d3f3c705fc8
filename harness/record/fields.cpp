#include "record/fields.h"

#include <cmath>
#include <limits>

namespace sb {
namespace {

using json = nlohmann::json;

std::string escape_token(const std::string& key) {
  std::string out;
  for (const char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// "a string", "an object", ...: what was found instead.
std::string found(const json& v) {
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_null()) return "null";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  if (v.is_number_integer()) return "a whole number";
  return "a number";
}

std::optional<double> number_of(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  return std::nullopt;
}

std::optional<std::string> string_of(const json& v) {
  if (!v.is_string()) return std::nullopt;
  return v.get<std::string>();
}

std::optional<int> int_of(const json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned())
    return v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())
               ? std::optional<int>(v.get<int>())
               : std::nullopt;
  const std::int64_t i = v.get<std::int64_t>();
  if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
    return std::nullopt;
  return static_cast<int>(i);
}

// The array `v` (member `key` of `f`), each element read by `element`
// (a "string", a "number", ...: `what`).
template <class T>
std::vector<T> elements(const Fields& f, const std::string& key, const json& v, const char* what,
                        std::optional<T> (*element)(const json&)) {
  if (!v.is_array())
    f.fail(key, std::string("expected an array of ") + what + "s, found " + found(v));
  std::vector<T> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::optional<T> e = element(v[i]);
    if (!e)
      throw RecordError(f.pointer_of(key) + "/" + std::to_string(i),
                        std::string("expected a ") + what + ", found " + found(v[i]));
    out.push_back(*e);
  }
  return out;
}

}  // namespace

RecordError::RecordError(std::string pointer, const std::string& problem)
    : std::runtime_error((pointer.empty() ? std::string("the record") : "at " + pointer) + ": " +
                         problem),
      pointer_(std::move(pointer)),
      problem_(problem) {}

json json_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

Fields::Fields(const json& value, std::string pointer)
    : value_(&value), pointer_(std::move(pointer)) {
  if (!value.is_object()) throw RecordError(pointer_, "expected an object, found " + found(value));
}

std::string Fields::pointer_of(const std::string& key) const {
  return pointer_ + "/" + escape_token(key);
}

bool Fields::has(const std::string& key) const { return value_->contains(key); }

std::vector<std::string> Fields::keys() const {
  std::vector<std::string> out;
  for (const auto& item : value_->items()) out.push_back(item.key());
  return out;
}

void Fields::fail(const std::string& key, const std::string& problem) const {
  throw RecordError(pointer_of(key), problem);
}

std::vector<Fields> Fields::objects(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array()) fail(key, "expected an array of objects, found " + found(v));
  std::vector<Fields> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    out.emplace_back(v[i], pointer_of(key) + "/" + std::to_string(i));
  return out;
}

const json& Fields::at(const std::string& key) const {
  const auto it = value_->find(key);
  if (it == value_->end()) fail(key, "missing");
  return *it;
}

template <>
std::string Fields::get<std::string>(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_string()) fail(key, "expected a string, found " + found(v));
  return v.get<std::string>();
}

template <>
bool Fields::get<bool>(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_boolean()) fail(key, "expected true or false, found " + found(v));
  return v.get<bool>();
}

template <>
double Fields::get<double>(const std::string& key) const {
  const json& v = at(key);
  const auto d = number_of(v);
  if (!d) fail(key, "expected a number (or \"nan\", \"inf\", \"-inf\"), found " + found(v));
  return *d;
}

template <>
std::int64_t Fields::get<std::int64_t>(const std::string& key) const {
  const json& v = at(key);
  if (v.is_number_unsigned() &&
      v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
    fail(key, "the whole number is too large");
  if (!v.is_number_integer()) fail(key, "expected a whole number, found " + found(v));
  return v.get<std::int64_t>();
}

template <>
std::uint64_t Fields::get<std::uint64_t>(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_number_integer()) fail(key, "expected a whole number, found " + found(v));
  if (!v.is_number_unsigned() && v.get<std::int64_t>() < 0)
    fail(key, "expected a whole number >= 0, found " + v.dump());
  return v.get<std::uint64_t>();
}

template <>
int Fields::get<int>(const std::string& key) const {
  const std::int64_t v = get<std::int64_t>(key);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail(key, "the whole number " + std::to_string(v) + " is out of range");
  return static_cast<int>(v);
}

template <>
std::vector<std::string> Fields::get<std::vector<std::string>>(const std::string& key) const {
  return elements<std::string>(*this, key, at(key), "string", string_of);
}

template <>
std::vector<double> Fields::get<std::vector<double>>(const std::string& key) const {
  return elements<double>(*this, key, at(key), "number", number_of);
}

template <>
std::vector<int> Fields::get<std::vector<int>>(const std::string& key) const {
  return elements<int>(*this, key, at(key), "whole number", int_of);
}

template <>
json Fields::get<json>(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_object()) fail(key, "expected an object, found " + found(v));
  return v;
}

Fields Fields::object(const std::string& key) const { return Fields(at(key), pointer_of(key)); }

std::optional<Fields> Fields::find_object(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return object(key);
}

}  // namespace sb
