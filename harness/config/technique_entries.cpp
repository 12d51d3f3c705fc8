#include "config/technique_entries.h"

#include <memory>

#include "config/sweeps.h"
#include "config/unknown_technique.h"
#include "core/error.h"

namespace sb::config {

using core::JobError;
using core::Params;
using core::ParamSpec;
using core::string_param;
using plugin::Registry;
using plugin::Technique;
using plugin::TechniqueInfo;

using json = nlohmann::json;

namespace {

// The variants of a technique that may be a failed plugin's: its parameters
// cannot be checked, so each sweep combination is named from the keys given.
std::vector<TechniqueVariant> unavailable_variants(const std::string& name,
                                                   const std::string& label, const json& params,
                                                   const std::string& p, const std::string& why,
                                                   const std::string& file) {
  auto stand_in = std::make_shared<TechniqueInfo>();
  stand_in->name = name;
  stand_in->summary = "unavailable: " + why;
  stand_in->create = [why](const Params&) -> std::unique_ptr<Technique> { throw JobError(why); };
  const std::vector<json> combos = expand_sweeps(params, file, p + "/params");  // checks params
  std::vector<ParamSpec> given;
  for (auto it = params.begin(); it != params.end(); ++it)
    given.push_back(string_param(it.key(), "", ""));  // only the name counts for naming
  std::vector<TechniqueVariant> out;
  for (const json& combo : combos) {
    TechniqueVariant v;
    v.info = stand_in.get();
    v.stand_in = stand_in;
    v.pointer = p;
    v.params = Params(combo);
    v.name = variant_name(label, given, combo);
    v.unavailable = why;
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace

// The variants of one technique entry: a name, or {"name", "params", "label"}
// whose list-valued params sweep.
std::vector<TechniqueVariant> technique_variants(const ConfigReader& r, const Registry& registry,
                                                 const json& given_entry, const std::string& p,
                                                 const std::string& file, bool may_be_unavailable) {
  json entry = given_entry;
  if (entry.is_string()) entry = json{{"name", entry}};
  r.object(entry, p, "a technique (a name or an object)");
  r.only_keys(entry, p, {"name", "params", "label", "own_map_size"});
  r.member(entry, p, "name");
  const bool own_map_size =
      entry.contains("own_map_size") && r.boolean(entry["own_map_size"], p + "/own_map_size");
  const std::string name = r.string(entry["name"], p + "/name");
  const TechniqueInfo* info = registry.find(name);
  const std::string label = entry.contains("label") ? r.label(entry["label"], p + "/label") : name;
  const json params = entry.value("params", json::object());
  std::vector<TechniqueVariant> out;
  if (info == nullptr) {
    const UnknownTechnique unknown = unknown_technique(name, registry, file);
    if (!unknown.plugin_failed || !may_be_unavailable)
      r.fail(p + (given_entry.is_string() ? "" : "/name"), unknown.message);
    // Perhaps the failed plugin's: its jobs fail, the others run.
    return unavailable_variants(name, label, params, p, unknown.message, file);
  }
  for (const json& combo : expand_sweeps(params, file, p + "/params")) {
    TechniqueVariant v;
    v.info = info;
    v.pointer = p;
    v.params = resolve_sweep_combo(info->params, params, combo, file, p + "/params");
    if (info->check) {
      const auto [param, problem] = info->check(v.params);
      if (!problem.empty()) r.fail(swept_pointer(params, combo, p + "/params", param), problem);
    }
    v.name = variant_name(label, info->params, combo);
    for (auto it = params.begin(); it != params.end(); ++it)
      if (it.value().is_array()) v.swept[it.key()] = combo[it.key()];
    v.given = combo;
    v.own_map_size = own_map_size;
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace sb::config
