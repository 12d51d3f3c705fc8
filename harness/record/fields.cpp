#include "record/fields.h"

#include <cmath>
#include <limits>

namespace sb::record {

using core::JsonReader;
using core::pointer_token;

namespace {

using json = nlohmann::json;

JsonReader record_reader() {
  return JsonReader([](const std::string& pointer, const std::string& problem) {
    throw RecordError(pointer, problem);
  });
}

// The array member `key` of `f`, each element read by `element` at its own
// pointer; `what` is what the array holds ("numbers").
template <class T, class Element>
std::vector<T> elements(const JsonReader& r, const std::string& pointer, const json& v,
                        const char* what, Element element) {
  r.array(v, pointer, what);
  std::vector<T> out;
  for (size_t i = 0; i < v.size(); ++i)
    out.push_back(element(v[i], pointer + "/" + std::to_string(i)));
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
    : reader_(record_reader()), value_(&value), pointer_(std::move(pointer)) {
  reader_.object(value, pointer_);
}

std::string Fields::pointer_of(const std::string& key) const {
  return pointer_ + "/" + pointer_token(key);
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
  const json& v = reader_.array(at(key), pointer_of(key), "objects");
  std::vector<Fields> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    out.emplace_back(v[i], pointer_of(key) + "/" + std::to_string(i));
  return out;
}

const json& Fields::at(const std::string& key) const {
  return reader_.member(*value_, pointer_, key);
}

std::string Fields::choice(const std::string& key, const std::vector<std::string>& choices) const {
  return reader_.choice(at(key), pointer_of(key), choices);
}

template <>
std::string Fields::get<std::string>(const std::string& key) const {
  return reader_.string(at(key), pointer_of(key));
}

template <>
bool Fields::get<bool>(const std::string& key) const {
  return reader_.boolean(at(key), pointer_of(key));
}

template <>
double Fields::get<double>(const std::string& key) const {
  return reader_.record_number(at(key), pointer_of(key));
}

template <>
std::int64_t Fields::get<std::int64_t>(const std::string& key) const {
  return reader_.integer(at(key), pointer_of(key), std::numeric_limits<std::int64_t>::min(),
                         std::numeric_limits<std::int64_t>::max());
}

template <>
std::uint64_t Fields::get<std::uint64_t>(const std::string& key) const {
  return reader_.unsigned_integer(at(key), pointer_of(key));
}

template <>
int Fields::get<int>(const std::string& key) const {
  return static_cast<int>(reader_.integer(at(key), pointer_of(key), std::numeric_limits<int>::min(),
                                          std::numeric_limits<int>::max()));
}

template <>
std::vector<std::string> Fields::get<std::vector<std::string>>(const std::string& key) const {
  return elements<std::string>(
      reader_, pointer_of(key), at(key), "strings",
      [&](const json& v, const std::string& p) { return reader_.string(v, p); });
}

template <>
std::vector<double> Fields::get<std::vector<double>>(const std::string& key) const {
  return elements<double>(
      reader_, pointer_of(key), at(key), "numbers",
      [&](const json& v, const std::string& p) { return reader_.record_number(v, p); });
}

template <>
std::vector<int> Fields::get<std::vector<int>>(const std::string& key) const {
  return elements<int>(
      reader_, pointer_of(key), at(key), "integers", [&](const json& v, const std::string& p) {
        return static_cast<int>(reader_.integer(v, p, std::numeric_limits<int>::min(),
                                                std::numeric_limits<int>::max()));
      });
}

template <>
json Fields::get<json>(const std::string& key) const {
  return reader_.object(at(key), pointer_of(key));
}

Fields Fields::object(const std::string& key) const { return Fields(at(key), pointer_of(key)); }

std::optional<Fields> Fields::find_object(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return object(key);
}

}  // namespace sb::record
