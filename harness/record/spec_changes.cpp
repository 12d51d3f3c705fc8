#include "record/spec_changes.h"

#include <set>

namespace sb::record {

using json = nlohmann::json;

namespace {

constexpr size_t kMaxValueChars = 80;
constexpr size_t kMaxNamedChanges = 3;

constexpr size_t kShownHashDigits = 12;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A SHA-256 as its first digits, as git shows a commit: enough to tell two apart.
std::string short_hash(const std::string& hex) {
  return hex.size() > kShownHashDigits ? hex.substr(0, kShownHashDigits) + ".." : hex;
}

// Strings as they are (a variant, an ISA), everything else as JSON.
std::string value_text(const json* v) {
  if (v == nullptr) return "absent";
  std::string text = v->is_string() ? v->get<std::string>() : v->dump();
  if (text.size() > kMaxValueChars) text = text.substr(0, kMaxValueChars - 3) + "...";
  return text;
}

// A member's value in a change line; hashes (…sha256) shortened.
std::string value_text(const json* v, const std::string& name) {
  if (v != nullptr && v->is_string() && ends_with(name, "sha256"))
    return short_hash(v->get<std::string>());
  return value_text(v);
}

// The SHA-256 a plugin member (spec technique.plugin) holds, or "".
std::string plugin_hash(const json& plugin) {
  const auto it = plugin.find("sha256");
  return it != plugin.end() && it->is_string() ? it->get<std::string>() : "";
}

void collect(const json* before, const json* after, const std::string& name,
             std::vector<std::string>& out) {
  // A rebuilt plugin is one change, named by its file, whatever else of it changed.
  if (before != nullptr && after != nullptr && before->is_object() && after->is_object() &&
      (name == "plugin" || ends_with(name, ".plugin")) &&
      plugin_hash(*before) != plugin_hash(*after)) {
    out.push_back("plugin " + after->value("file", std::string("?")) + " changed (sha256 " +
                  short_hash(plugin_hash(*before)) + " -> " + short_hash(plugin_hash(*after)) +
                  ")");
    return;
  }
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
  out.push_back((name.empty() ? std::string("spec") : name) + " changed (" +
                value_text(before, name) + " -> " + value_text(after, name) + ")");
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

}  // namespace sb::record
