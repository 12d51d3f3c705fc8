#pragma once
// Each record struct is described once, by a static member
//
//   template <class V> static void describe(V& v);
//
// that names its members to a visitor V: record/record_json.h writes and
// reads the JSON from it, record/record_schema.h makes docs/results.md's
// schema tables. So a member added to a struct is added to its JSON, its
// reader and its documentation in one place, and they cannot drift.
//
// What a description may say (V is any of the visitors):
//   v.field(key, &S::member, {unit, doc, presence, suffixed, display})
//       a member: a number, integer, bool, string, list, nlohmann::json,
//       std::array<double, N>, a described struct, std::map<std::string, T>
//       of those, an std::vector of described structs (a JSON array of
//       objects), or std::optional of any (absent when nullopt)
//   v.object(key, {unit, doc}, [](auto& sub) { sub.field(...); })
//       a JSON object of S's own members (record["stability"]["flicker"]
//       ["reference"]): no struct of its own
//   v.flatten(&S::optional_part, {unit, doc})
//       the members of a described struct, at S's level, present together
//       or not at all (a scene's members once it was built)
//   v.custom(key, type, {unit, doc}, write, read)
//       what no member spells: write(const S&) → std::optional<json> (nullopt:
//       absent), read(S&, const Fields& of S) (max_pixel, the classes' rows)
// A struct with `static void check(const S&, const Fields&)` is checked by it
// once read: what one member says about another (the control's samples pair
// with the job's).
#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace sb::record {

// When a member is in a record's JSON.
enum class Presence {
  Natural,      // std::optional: WhenSet; anything else: Always
  Always,       // written always; a record without it is refused
  WhenSet,      // an std::optional, written when set
  UnlessEmpty,  // written unless empty (a list, a map, a string, a struct's
                // empty()); read as empty when absent
  OlderLack,    // written always; absent from older records, which read as
                // the member's default
};

// Which way a figure improves: reports mark the best value, comparisons call
// a change a regression or an improvement by it.
enum class Better { Neither, Lower, Higher };

// How reports show a figure (record/figures.h): its name in words ("RMSE",
// "Penumbra"), which way it improves and the printf format of its value.
// Empty for a member that no report shows.
struct Display {
  const char* label = "";
  Better better = Better::Neither;
  const char* format = nullptr;
};

struct FieldInfo {
  const char* unit = "";  // "ms", "s", "px", "degrees"; "" for none
  const char* doc = "";   // one line for docs/results.md
  Presence presence = Presence::Natural;
  // The key takes the unit of the series it is in as a suffix ("median" →
  // "median_ms" in a timing series, "median" in a ratio series): what lets
  // one Series type serve both.
  bool suffixed = false;
  Display display = {};
};

namespace describe_detail {

template <class T>
struct Optional : std::false_type {};
template <class T>
struct Optional<std::optional<T>> : std::true_type {
  using type = T;
};

template <class T>
struct NameMap : std::false_type {};
template <class T>
struct NameMap<std::map<std::string, T>> : std::true_type {
  using type = T;
};

template <class T>
struct List : std::false_type {};
template <class T>
struct List<std::vector<T>> : std::true_type {
  using type = T;
};

template <class T>
struct Numbers : std::false_type {};
template <std::size_t N>
struct Numbers<std::array<double, N>> : std::true_type {
  static constexpr std::size_t size = N;
};

}  // namespace describe_detail

// A described struct's name and what it is, for its schema table.
struct RecordDoc {
  const char* name;
  const char* doc;
};

// A struct with a description: `static constexpr RecordDoc kSchema` and
// describe().
template <class T>
concept Described = requires {
  T::kSchema;
};

// An std::vector of described structs: a JSON array of objects.
template <class T>
concept DescribedList =
    describe_detail::List<T>::value && Described<typename describe_detail::List<T>::type>;

// The presence a member of type M has under `p`.
template <class M>
constexpr Presence presence_of(Presence p) {
  if (p != Presence::Natural) return p;
  return describe_detail::Optional<M>::value ? Presence::WhenSet : Presence::Always;
}

// The key of a member within a series of `suffix` ("_ms" or "").
inline std::string key_of(const char* key, const FieldInfo& info, const std::string& suffix) {
  return info.suffixed ? key + suffix : std::string(key);
}

// The suffix a described member's own suffixed keys take: its unit's.
inline std::string suffix_of(const FieldInfo& info) {
  if (info.unit[0] == '\0') return {};
  std::string suffix = "_";  // not "_" + ...: see InputError::format (core/error.h)
  suffix += info.unit;
  return suffix;
}

}  // namespace sb::record
