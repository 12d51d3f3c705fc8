#pragma once
// The one reader of JSON values by JSON pointer (RFC 6901): it checks a
// value's type and range and, when they are wrong, fails at the value's
// pointer with one phrasing, "expected X, found Y", where Y is the found
// value described by describe() when its type is wrong ("string \"64\"") and
// its text when its type is right but not its value ("0").
//
// Who reads what, and what a failure throws, is the caller's: a config
// (config/config_reader.h: InputError naming the file), a technique or scene
// parameter (core/params.h: InputError naming the parameter), a run record
// (record/fields.h: RecordError). Each passes the function that throws.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sb::core {

// "number 3.5", "string \"abc\"", "null": a found value's type and JSON text,
// cut at 60 bytes. Bytes that are not UTF-8 show as U+FFFD.
std::string describe(const nlohmann::json& v);

// `key` as one token of a JSON pointer: "~" as "~0", "/" as "~1".
std::string pointer_token(const std::string& key);

// A bound of a range as a message spells it: 1, 0.5, 1e+300.
std::string range_bound(double v);

class JsonReader {
 public:
  // Throws an exception about the value at `pointer` ("" for the whole
  // document); it must not return.
  using Fail = std::function<void(const std::string& pointer, const std::string& problem)>;
  explicit JsonReader(Fail fail) : fail_(std::move(fail)) {}

  [[noreturn]] void fail(const std::string& pointer, const std::string& problem) const;

  // An object; `what` names it: "expected frame counts (an object), ...".
  const nlohmann::json& object(const nlohmann::json& v, const std::string& pointer,
                               const std::string& what = "") const;
  // The member `key` of the object `obj` (at `pointer`). Missing, it fails
  // at the object, which is where the key would go:
  // "missing required key \"timed\" in this object".
  const nlohmann::json& member(const nlohmann::json& obj, const std::string& pointer,
                               const std::string& key) const;
  // Fails at the first member whose key is not in `allowed`:
  // "unknown key 'x' (expected one of: a, b)", then "; did you mean a?" for
  // a likely typo (core/nearest_names.h); `noun` names what a key is.
  void only_keys(const nlohmann::json& obj, const std::string& pointer,
                 const std::vector<std::string>& allowed, const std::string& noun = "key") const;
  // An array; `what` is what the array holds: "expected an array of numbers".
  const nlohmann::json& array(const nlohmann::json& v, const std::string& pointer,
                              const std::string& what) const;

  std::string string(const nlohmann::json& v, const std::string& pointer) const;
  bool boolean(const nlohmann::json& v, const std::string& pointer) const;
  // One of `choices`: "expected one of \"a\", \"b\", found \"c\"".
  std::string choice(const nlohmann::json& v, const std::string& pointer,
                     const std::vector<std::string>& choices) const;
  // An integer in [lo, hi]; with `whole_floats`, also a number without a
  // fraction (2.0), as technique parameters accept.
  std::int64_t integer(const nlohmann::json& v, const std::string& pointer, std::int64_t lo,
                       std::int64_t hi, bool whole_floats = false) const;
  // An integer >= 0, up to 2^64 - 1.
  std::uint64_t unsigned_integer(const nlohmann::json& v, const std::string& pointer) const;
  // A finite number in [lo, hi].
  double number(const nlohmann::json& v, const std::string& pointer, double lo = -1e300,
                double hi = 1e300) const;
  // A run record's number: any number, or NaN and ±inf spelled "nan",
  // "inf" and "-inf" (which JSON cannot spell).
  double record_number(const nlohmann::json& v, const std::string& pointer) const;
  // A value an extra rule refused: "expected <expected>, found <its text>".
  [[noreturn]] void refuse(const nlohmann::json& v, const std::string& pointer,
                           const std::string& expected) const;

 private:
  Fail fail_;
};

}  // namespace sb::core
