#include "record/spec_changes.h"

#include <set>

namespace sb {

using json = nlohmann::json;

namespace {

constexpr size_t kMaxValueChars = 80;
constexpr size_t kMaxNamedChanges = 3;

// Strings as they are (a variant, an ISA), everything else as JSON.
std::string value_text(const json* v) {
  if (v == nullptr) return "absent";
  std::string text = v->is_string() ? v->get<std::string>() : v->dump();
  if (text.size() > kMaxValueChars) text = text.substr(0, kMaxValueChars - 3) + "...";
  return text;
}

void collect(const json* before, const json* after, const std::string& name,
             std::vector<std::string>& out) {
  if (before != nullptr && after != nullptr && before->is_object() && after->is_object()) {
    std::set<std::string> keys;  // both sides' members, in key order
    for (auto it = before->begin(); it != before->end(); ++it) keys.insert(it.key());
    for (auto it = after->begin(); it != after->end(); ++it) keys.insert(it.key());
    for (const std::string& key : keys) {
      const auto b = before->find(key);
      const auto a = after->find(key);
      std::string member = name;
      if (!member.empty()) member += '.';
      member += key;
      collect(b == before->end() ? nullptr : &*b, a == after->end() ? nullptr : &*a, member, out);
    }
    return;
  }
  if (before != nullptr && after != nullptr && *before == *after) return;
  out.push_back((name.empty() ? std::string("spec") : name) + " changed (" + value_text(before) +
                " -> " + value_text(after) + ")");
}

}  // namespace

std::vector<std::string> spec_changes(const json& before, const json& after) {
  std::vector<std::string> out;
  collect(&before, &after, "", out);
  return out;
}

std::string rerun_reason(const JobRecord& earlier, const json& spec, const std::string& hash) {
  if (earlier.spec_hash == hash) return "";
  if (!earlier.spec)
    return "its record stores no spec (written before records kept the settings they were run "
           "with), so its settings cannot be checked";
  const std::vector<std::string> changes = spec_changes(*earlier.spec, spec);
  // Equal settings under another hash: the record was edited, or the hash
  // is not of its spec.
  if (changes.empty()) return "its spec_hash is not that of its stored spec";
  std::string reason;
  for (size_t i = 0; i < changes.size() && i < kMaxNamedChanges; ++i)
    reason += (i == 0 ? "" : "; ") + changes[i];
  if (changes.size() > kMaxNamedChanges)
    reason += "; and " + std::to_string(changes.size() - kMaxNamedChanges) + " more";
  return reason;
}

}  // namespace sb
