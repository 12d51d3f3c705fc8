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

// A file's identity in a spec (config/identity.h, file_identity):
// {"sha256": ..., "reads": {name: sha256}}; a plugin's has a "file" too.
bool file_identity(const json& v) {
  if (!v.is_object() || !v.contains("sha256")) return false;
  for (auto it = v.begin(); it != v.end(); ++it)
    if (it.key() != "sha256" && it.key() != "reads") return false;
  return true;
}

// A hash as a change line shows it: short, "unreadable" for null.
std::string content_text(const json* sha) {
  if (sha == nullptr) return "absent";
  return sha->is_string() ? short_hash(sha->get<std::string>()) : std::string("unreadable");
}

// One line per file whose content differs: the file itself, then each file
// read through it, named by `label` (its path, where the record says it).
void file_changes(const json& before, const json& after, const std::string& label,
                  std::vector<std::string>& out) {
  if (before["sha256"] != after["sha256"])
    out.push_back("file " + label + ": content changed (sha256 " + content_text(&before["sha256"]) +
                  " -> " + content_text(&after["sha256"]) + ")");
  const json none = json::object();
  const json& b = before.contains("reads") ? before["reads"] : none;
  const json& a = after.contains("reads") ? after["reads"] : none;
  std::set<std::string> names;
  for (auto it = b.begin(); it != b.end(); ++it) names.insert(it.key());
  for (auto it = a.begin(); it != a.end(); ++it) names.insert(it.key());
  for (const std::string& n : names) {
    const json* was = b.contains(n) ? &b[n] : nullptr;
    const json* now = a.contains(n) ? &a[n] : nullptr;
    if (was != nullptr && now != nullptr && *was == *now) continue;
    std::string line = "file ";
    line.append(n).append(" of ").append(label).append(": content changed (sha256 ");
    line.append(content_text(was)).append(" -> ").append(content_text(now)).append(")");
    out.push_back(std::move(line));
  }
}

void collect(const json* before, const json* after, const std::string& name, const json& labels,
             std::vector<std::string>& out) {
  // A file is named by its path, never by its place in the spec, and says
  // that its content changed.
  if (before != nullptr && after != nullptr && file_identity(*before) && file_identity(*after)) {
    const auto label = labels.find(name);
    file_changes(*before, *after,
                 label != labels.end() && label->is_string() ? label->get<std::string>() : name,
                 out);
    return;
  }
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
      collect(b == before->end() ? nullptr : &*b, a == after->end() ? nullptr : &*a, member, labels,
              out);
    }
    return;
  }
  if (before != nullptr && after != nullptr && *before == *after) return;
  out.push_back((name.empty() ? std::string("spec") : name) + " changed (" +
                value_text(before, name) + " -> " + value_text(after, name) + ")");
}

}  // namespace

std::vector<std::string> spec_changes(const json& before, const json& after, const json& labels) {
  std::vector<std::string> out;
  collect(&before, &after, "", labels.is_object() ? labels : json::object(), out);
  return out;
}

std::string rerun_reason(const JobRecord& earlier, const json& spec, const std::string& hash) {
  if (earlier.spec_hash == hash) return "";
  if (!earlier.spec)
    return "its record stores no spec (written before records kept the settings they were run "
           "with), so its settings cannot be checked";
  // A file parameter's identity is named by the path the record was run with.
  json labels = json::object();
  const auto label = [&](const std::string& where, const json& params) {
    if (!params.is_object()) return;
    for (auto it = params.begin(); it != params.end(); ++it)
      if (it->is_string()) labels[where + "." + it.key()] = *it;
  };
  label("scene.params", earlier.scene.params);
  label("technique.params", earlier.technique.params);
  const std::vector<std::string> changes = spec_changes(*earlier.spec, spec, labels);
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
