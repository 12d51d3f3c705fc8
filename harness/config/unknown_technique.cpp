#include "config/unknown_technique.h"

#include <filesystem>
#include <vector>

#include "core/nearest_names.h"

namespace sb::config {

namespace fs = std::filesystem;

using core::did_you_mean;
using plugin::PluginLoadFailure;
using plugin::Registry;

namespace {

// The module new-technique's README builds for `name`, beside the config
// (build/NAME.so), when it exists: "" else.
std::string unloaded_module(const std::string& name, const std::string& config_file) {
  if (config_file.empty()) return "";
  const fs::path module = fs::path(config_file).parent_path() / "build" / (name + ".so");
  std::error_code ec;
  if (!fs::is_regular_file(module, ec)) return "";
  const fs::path dir = fs::absolute(module, ec).parent_path();
  return "\n  " + (dir / module.filename()).string() +
         " (new-technique's build of it) would provide it: export SHADOWBENCH_PLUGIN_PATH=" +
         dir.string();
}

}  // namespace

UnknownTechnique unknown_technique(const std::string& name, const Registry& registry,
                                   const std::string& config_file) {
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
  if (std::string hint = did_you_mean(name, known, false); !hint.empty()) out.message += ";" + hint;
  // Where plugins were looked for, unless a failed one is the likelier cause.
  if (!out.plugin_failed && !registry.search_hint().empty())
    out.message += "\n  " + registry.search_hint();
  if (!out.plugin_failed) out.message += unloaded_module(name, config_file);
  return out;
}

}  // namespace sb::config
