#pragma once
// Reading a record's JSON value by value, each named by its JSON pointer
// (RFC 6901), so that whatever is wrong with a record is reported with its
// place: "at /timing/frame/median_ms: expected a number (or \"nan\", \"inf\",
// \"-inf\"), found string \"fast\"". The checks and their messages are the one
// JSON reader's (core/json_reader.h); the reader of a file adds the file's
// name (store/results_store.h).
//
// Numbers: NaN and ±inf have no JSON spelling, so a record writes them as the
// strings "nan", "inf" and "-inf" (json_number); reading a number accepts
// those three strings and nothing else that is not a number.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/json_reader.h"

namespace sb::record {

// A record that does not follow its schema, and where.
class RecordError : public std::runtime_error {
 public:
  RecordError(std::string pointer, const std::string& problem);
  const std::string& pointer() const { return pointer_; }  // "" for the whole record
  const std::string& problem() const { return problem_; }

 private:
  std::string pointer_;
  std::string problem_;
};

// A number for a record: NaN and ±inf as "nan", "inf", "-inf".
nlohmann::json json_number(double v);

// The members of one JSON object of a record.
class Fields {
 public:
  // Throws RecordError (at `pointer`) unless `value` is an object.
  Fields(const nlohmann::json& value, std::string pointer);

  const std::string& pointer() const { return pointer_; }
  std::string pointer_of(const std::string& key) const;
  bool has(const std::string& key) const;
  std::vector<std::string> keys() const;  // in the object's order

  // A required member: a RecordError names it when it is of another type,
  // and this object when it is missing. T is one of std::string, bool, double, int, std::int64_t,
  // std::uint64_t, std::vector<std::string>, std::vector<double>,
  // std::vector<int>, or
  // nlohmann::json (any object, kept as it is).
  template <class T>
  T get(const std::string& key) const;
  // An optional member: nullopt when absent; present, it must be of type T.
  template <class T>
  std::optional<T> find(const std::string& key) const {
    return has(key) ? std::optional<T>(get<T>(key)) : std::nullopt;
  }
  // A member that is an object.
  Fields object(const std::string& key) const;
  std::optional<Fields> find_object(const std::string& key) const;
  // A member that is an array of objects, each read at its own pointer
  // ("/jobs/3").
  std::vector<Fields> objects(const std::string& key) const;

  // The member `key`, a string, one of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const;

  // A RecordError at this object's member `key`.
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  const nlohmann::json& at(const std::string& key) const;
  core::JsonReader reader_;
  const nlohmann::json* value_;
  std::string pointer_;
};

template <>
std::string Fields::get<std::string>(const std::string& key) const;
template <>
bool Fields::get<bool>(const std::string& key) const;
template <>
double Fields::get<double>(const std::string& key) const;
template <>
int Fields::get<int>(const std::string& key) const;
template <>
std::int64_t Fields::get<std::int64_t>(const std::string& key) const;
template <>
std::uint64_t Fields::get<std::uint64_t>(const std::string& key) const;
template <>
std::vector<std::string> Fields::get<std::vector<std::string>>(const std::string& key) const;
template <>
std::vector<double> Fields::get<std::vector<double>>(const std::string& key) const;
template <>
std::vector<int> Fields::get<std::vector<int>>(const std::string& key) const;
template <>
nlohmann::json Fields::get<nlohmann::json>(const std::string& key) const;

}  // namespace sb::record
