#include "config/unknown_technique.h"

#include <filesystem>
#include <vector>

#include "core/nearest_names.h"

namespace sb::config {

using core::did_you_mean;
using plugin::PluginLoadFailure;
using plugin::Registry;

UnknownTechnique unknown_technique(const std::string& name, const Registry& registry) {
  std::vector<std::string> known;
  for (const auto& t : registry.all()) known.push_back(t.name);
  UnknownTechnique out;
  out.message = "unknown technique \"" + name + "\" (";
  // A module named for the technique is the one to blame; else any that failed.
  std::vector<const PluginLoadFailure*> blamed;
  for (const auto& f : registry.load_failures())
    if (std::filesystem::path(f.file).stem() == name) blamed.push_back(&f);
  if (blamed.empty())
    for (const auto& f : registry.load_failures()) blamed.push_back(&f);
  out.plugin_failed = !blamed.empty();
  if (blamed.size() == 1) {
    out.message += "plugin " + blamed[0]->file + " failed to load: " + blamed[0]->message;
  } else if (!blamed.empty()) {
    out.message += std::to_string(blamed.size()) + " plugins failed to load: ";
    for (size_t i = 0; i < blamed.size(); ++i)
      out.message += (i == 0 ? "" : "; ") + blamed[i]->file + ": " + blamed[i]->message;
  } else {
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    out.message += "registered: " + list;
  }
  out.message += ")";
  if (std::string hint = did_you_mean(name, known); !hint.empty()) out.message += ";" + hint;
  // Where plugins were looked for, unless a failed one is the likelier cause.
  if (!out.plugin_failed && !registry.search_hint().empty())
    out.message += "\n  " + registry.search_hint();
  return out;
}

}  // namespace sb::config
