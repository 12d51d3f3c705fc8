#include "config/identity.h"

#include "config/config_blocks.h"
#include "core/scene_types.h"
#include "core/sha256.h"
#include "plugin/plugin_identity.h"

namespace sb::config {

using core::Decides;
using core::InputFile;
using core::Params;
using core::ParamSpec;
using plugin::PluginIdentity;

using json = nlohmann::json;

json file_identity(const std::string& path, const std::vector<InputFile>& inputs) {
  json id = {{"sha256", nullptr}};
  // The file itself, and what was read through it, are consecutive: the
  // file ("" name), then its reads (named), until the next file.
  bool found = false;
  json reads = json::object();
  for (const InputFile& f : inputs) {
    if (f.name.empty()) {
      if (found) break;
      found = f.path == path;
      if (found) id["sha256"] = f.sha256;
    } else if (found) {
      reads[f.name] = f.sha256;
    }
  }
  if (!found) {
    const std::optional<std::string> sha = core::sha256_file_hex(path);
    if (sha) id["sha256"] = *sha;
  }
  if (!reads.empty()) id["reads"] = std::move(reads);
  return id;
}

json params_identity(const std::vector<ParamSpec>& specs, const Params& params,
                     const std::vector<InputFile>& inputs) {
  const json& values = params.json();
  if (specs.empty()) return values;
  json out = json::object();
  for (const ParamSpec& s : specs) {
    if (s.decides == Decides::None || !values.contains(s.name)) continue;
    const json& v = values[s.name];
    out[s.name] = s.is_path && v.is_string() ? file_identity(v.get<std::string>(), inputs) : v;
  }
  return out;
}

json technique_identity(const Experiment& e, const TechniqueVariant& tv) {
  json t = {{"name", tv.info->name}, {"params", params_identity(tv.info->params, tv.params)}};
  const PluginIdentity* p = e.registry == nullptr ? nullptr : e.registry->plugin_of(tv.info->name);
  if (p != nullptr)
    t["plugin"] = {{"file", p->file}, {"sha256", p->sha256}, {"api_version", p->api_version}};
  return t;
}

const std::vector<SceneEntryKey>& scene_entry_keys() {
  static const std::vector<SceneEntryKey> keys{
      {"light", Decides::Both, [](const SceneVariant& sv) { return sv.light; },
       json{{"size", 2.0}}},
      {"camera", Decides::Both, [](const SceneVariant& sv) { return sv.camera; },
       json{{"fov_y", 30.0}}},
      // A name: it makes the job id, not the numbers.
      {"label", Decides::None, nullptr, "other_label"},
      {"infer_receivers", Decides::Both,
       [](const SceneVariant& sv) { return json(sv.infer_receivers); }, false},
      // The stability table's threshold: whether a job is degraded.
      {"max_rmse", Decides::Error,
       [](const SceneVariant& sv) { return sv.max_rmse ? json(*sv.max_rmse) : json(nullptr); },
       0.25},
  };
  return keys;
}

json scene_identity(const SceneVariant& sv, const std::vector<InputFile>& inputs) {
  const core::SceneType* type = core::find_scene_type(sv.type);
  json id = {{"type", sv.type},
             {"params", params_identity(type != nullptr ? type->params : std::vector<ParamSpec>{},
                                        sv.params, inputs)}};
  for (const SceneEntryKey& k : scene_entry_keys())
    if (k.decides != Decides::None) id[k.name] = k.value(sv);
  return id;
}

json blocks_identity(const Experiment& e) {
  json out = json::object();
  for (const ConfigBlock& b : config_blocks()) {
    json keys = json::object();
    for (const BlockKey& k : b.keys)
      if (k.spec.decides != Decides::None) keys[k.spec.name] = nullptr;
    if (keys.empty()) continue;
    if (b.in_effect && !b.in_effect(e)) {
      out[b.name] = nullptr;
      continue;
    }
    for (const BlockKey& k : b.keys)
      if (k.spec.decides != Decides::None)
        keys[k.spec.name] = k.identity ? k.identity(e) : k.value(e);
    out[b.name] = std::move(keys);
  }
  return out;
}

}  // namespace sb::config
