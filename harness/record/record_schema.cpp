#include "record/record_schema.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <deque>
#include <map>
#include <sstream>
#include <type_traits>

#include "record/job_record.h"
#include "record/plan_record.h"

namespace sb::record {
namespace {

using describe_detail::List;
using describe_detail::NameMap;
using describe_detail::Numbers;
using describe_detail::Optional;

struct Row {
  std::string key, type, unit, present, doc;
};

struct Table {
  std::string name, doc;
  std::vector<std::string> at;  // the pointers it stands at
  std::vector<Row> rows;
};

struct Schema {
  std::deque<Table> tables;  // in the order first met; a deque, so that a table stays put
  std::map<std::string, size_t> index;
  RecordPointers pointers;
};

template <class T>
std::string type_name() {
  if constexpr (Optional<T>::value) {
    return type_name<typename Optional<T>::type>();
  } else if constexpr (Described<T>) {
    std::string anchor = T::kSchema.name;
    for (char& c : anchor) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return std::string("[`") + T::kSchema.name + "`](#" + anchor + ")";
  } else if constexpr (DescribedList<T>) {
    return "array of " + type_name<typename List<T>::type>();
  } else if constexpr (NameMap<T>::value) {
    return "name → " + type_name<typename NameMap<T>::type>();
  } else if constexpr (Numbers<T>::value) {
    return std::to_string(Numbers<T>::size) + " numbers";
  } else if constexpr (std::is_same_v<T, bool>) {
    return "boolean";
  } else if constexpr (std::is_same_v<T, double>) {
    return "number";
  } else if constexpr (std::is_integral_v<T>) {
    return "integer";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "string";
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    return "array of strings";
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return "array of numbers";
  } else {
    static_assert(std::is_same_v<T, nlohmann::json>, "a member type the schema cannot name");
    return "object, as it is";
  }
}

std::string present_text(Presence p, const std::string& together) {
  switch (p) {
    case Presence::WhenSet:
      return "when set";
    case Presence::UnlessEmpty:
      return "unless empty";
    case Presence::OlderLack:
      return together.empty() ? "always; older records lack it" : together;
    case Presence::Natural:
    case Presence::Always:
      break;
  }
  return together.empty() ? "always" : together;
}

template <class S>
class Walker;

// Walks a described struct standing at `pointer`: its table once, its
// pointers at every place.
template <class T>
void walk_struct(Schema& schema, const std::string& pointer, const std::string& suffix) {
  Table* table = nullptr;
  const auto it = schema.index.find(T::kSchema.name);
  if (it == schema.index.end()) {
    schema.index[T::kSchema.name] = schema.tables.size();
    schema.tables.push_back({T::kSchema.name, T::kSchema.doc, {}, {}});
    table = &schema.tables.back();
  }
  schema.tables[schema.index[T::kSchema.name]].at.push_back(pointer.empty() ? "/" : pointer);
  Walker<T> w(schema, table, pointer, suffix, "", "");
  T::describe(w);
}

template <class T>
void walk_value(Schema& schema, const std::string& pointer, const std::string& suffix) {
  if constexpr (Optional<T>::value) {
    walk_value<typename Optional<T>::type>(schema, pointer, suffix);
    return;
  }
  schema.pointers.members.push_back(pointer);
  if constexpr (Described<T>)
    walk_struct<T>(schema, pointer, suffix);
  else if constexpr (DescribedList<T>)
    walk_struct<typename List<T>::type>(schema, pointer + "/*", suffix);
  else if constexpr (NameMap<T>::value)
    walk_value<typename NameMap<T>::type>(schema, pointer + "/*", suffix);
  else if constexpr (std::is_same_v<T, nlohmann::json>)
    schema.pointers.opaque.push_back(pointer);
}

template <class S>
class Walker {
 public:
  // `table` is null where S's table is made already; `prefix` names the
  // keys of an object() ("fine."), `together` when a flattened part is there.
  Walker(Schema& schema, Table* table, std::string pointer, std::string suffix, std::string prefix,
         std::string together)
      : schema_(schema),
        table_(table),
        pointer_(std::move(pointer)),
        suffix_(std::move(suffix)),
        prefix_(std::move(prefix)),
        together_(std::move(together)) {}

  template <class M>
  void field(const char* key, M S::* /*member*/, const FieldInfo& info = {}) {
    row(std::string(key) + (info.suffixed ? " †" : ""), type_name<M>(), info,
        presence_of<M>(info.presence));
    walk_value<M>(schema_, pointer_ + "/" + key_of(key, info, suffix_), suffix_of(info));
  }
  template <class F>
  void object(const char* key, const FieldInfo& info, F&& members) {
    row(key, "object", info, Presence::Always);
    const std::string at = pointer_ + "/" + key;
    schema_.pointers.members.push_back(at);
    Walker sub(schema_, table_, at, suffix_, prefix_ + key + ".", together_);
    members(sub);
  }
  template <class T>
  void flatten(std::optional<T> S::* /*member*/, const FieldInfo& info) {
    Walker<T> sub(schema_, table_, pointer_, suffix_, prefix_, info.doc);
    T::describe(sub);
  }
  template <class W, class R>
  void custom(const char* key, const char* type, const FieldInfo& info, W&& /*write*/,
              R&& /*read*/) {
    row(key, type, info, presence_of<int>(info.presence));
    const std::string at = pointer_ + "/" + key;
    schema_.pointers.members.push_back(at);
    schema_.pointers.opaque.push_back(at);
  }

 private:
  template <class>
  friend class Walker;

  void row(const std::string& key, const std::string& type, const FieldInfo& info, Presence p) {
    if (table_ != nullptr)
      table_->rows.push_back(
          {"`" + prefix_ + key + "`", type, info.unit, present_text(p, together_), info.doc});
  }

  Schema& schema_;
  Table* table_;
  std::string pointer_, suffix_, prefix_, together_;
};

std::string cell(const std::string& s) {
  std::string out;
  for (const char c : s) out += c == '|' ? "\\|" : std::string(1, c);
  return out;
}

template <class Root>
Schema schema_of() {
  Schema schema;
  walk_struct<Root>(schema, "", "");
  return schema;
}

std::string markdown(const Schema& schema) {
  std::ostringstream out;
  for (const Table& t : schema.tables) {
    out << "#### " << t.name << "\n\n";
    if (!t.doc.empty()) {
      std::string doc = cell(t.doc);
      doc[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(doc[0])));
      out << doc << ". ";
    }
    out << "At";
    for (size_t i = 0; i < t.at.size(); ++i) out << (i == 0 ? " `" : ", `") << t.at[i] << "`";
    out << ".\n\n| key | type | unit | present | meaning |\n|---|---|---|---|---|\n";
    for (const Row& r : t.rows)
      out << "| " << r.key << " | " << r.type << " | " << r.unit << " | " << r.present << " | "
          << cell(r.doc) << " |\n";
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::string record_schema_markdown() { return markdown(schema_of<JobRecord>()); }
RecordPointers record_pointers() { return schema_of<JobRecord>().pointers; }
std::string plan_schema_markdown() { return markdown(schema_of<PlanRecord>()); }
RecordPointers plan_pointers() { return schema_of<PlanRecord>().pointers; }

namespace {

// "/a/b" → {"a", "b"}; no unescaping: the schema's keys hold no "~" or "/".
std::vector<std::string> tokens(const std::string& pointer) {
  std::vector<std::string> out;
  for (size_t at = 0; at < pointer.size();) {
    const size_t end = std::min(pointer.find('/', at + 1), pointer.size());
    out.push_back(pointer.substr(at + 1, end - at - 1));
    at = end;
  }
  return out;
}

}  // namespace

bool pointer_matches(const std::string& pattern, const std::string& pointer) {
  const std::vector<std::string> a = tokens(pattern), b = tokens(pointer);
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != "*" && a[i] != b[i]) return false;
  return true;
}

}  // namespace sb::record
