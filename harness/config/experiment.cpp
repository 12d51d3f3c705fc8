#include "config/experiment.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "config/config_blocks.h"
#include "config/config_reader.h"
#include "config/identity.h"
#include "config/json_file.h"
#include "config/resolutions.h"
#include "config/scene_overrides.h"
#include "config/sweeps.h"
#include "config/technique_entries.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/names.h"
#include "core/nearest_names.h"
#include "core/scene_setup_check.h"

namespace sb::config {

using core::describe;
using core::did_you_mean;
using core::find_scene_type;
using core::Hasher;
using core::InputError;
using core::job_id;
using core::JsonPositions;
using core::located;
using core::Params;
using core::ParamSpec;
using core::Scene;
using core::scene_setup_problem;
using core::scene_types;
using core::SceneType;
using plugin::Registry;

namespace {

using json = nlohmann::json;

// Path parameters are relative to the config file's folder.
Params resolve_paths(const std::vector<ParamSpec>& specs, const Params& params,
                     const std::string& config_file) {
  json values = params.json();
  const std::filesystem::path base = std::filesystem::path(config_file).parent_path();
  for (const auto& s : specs) {
    if (!s.is_path) continue;
    const std::filesystem::path given = values[s.name].get<std::string>();
    if (given.is_relative()) values[s.name] = (base / given).lexically_normal().string();
  }
  return Params(std::move(values));
}

}  // namespace

json StabilityConfig::to_json() const {
  return {{"flicker_frames", flicker_frames},
          {"flicker_step", flicker_step},
          {"flicker_factor", flicker_factor},
          {"sensitivity", sensitivity},
          {"sensitivity_step", sensitivity_step},
          {"stiff_threshold", stiff_threshold},
          {"max_rmse", max_rmse}};
}

Experiment parse_experiment(const json& doc, const std::string& file, const Registry& registry,
                            const ExperimentLimits& limits) {
  ConfigReader r(file);
  r.object(doc, "", "an experiment");
  r.only_keys(doc, "",
              {"name", "description", "scenes", "techniques", "resolutions", "frames", "reference",
               "stability", "metrics", "limits"});
  check_job_count(r, doc, limits);
  Experiment e;
  e.file = file;
  e.registry = &registry;
  e.name = doc.contains("name") ? r.string(doc["name"], "/name") : "experiment";
  // It names the run folder: a plain file name.
  const bool plain_name = !e.name.empty() && e.name.size() <= 100 && e.name[0] != '.' &&
                          std::all_of(e.name.begin(), e.name.end(), [](char c) {
                            return std::isalnum(static_cast<unsigned char>(c)) || c == '.' ||
                                   c == '-' || c == '_' || c == '=' || c == '+';
                          });
  if (!plain_name)
    r.fail("/name",
           "expected at most 100 letters, digits and . _ - = + (not starting with '.'), found " +
               describe(doc["name"]));
  if (doc.contains("description")) e.description = r.string(doc["description"], "/description");

  // Scenes.
  const json& scenes = r.member(doc, "", "scenes");
  if (!scenes.is_array() || scenes.empty())
    r.fail("/scenes", "expected a non-empty list of scenes, found " + describe(scenes));
  std::set<std::string> names;
  for (size_t i = 0; i < scenes.size(); ++i) {
    const std::string p = "/scenes/" + std::to_string(i);
    const json& entry = r.object(scenes[i], p, "a scene");
    std::vector<std::string> entry_keys{"type", "params"};
    for (const SceneEntryKey& k : scene_entry_keys()) entry_keys.push_back(k.name);
    r.only_keys(entry, p, entry_keys);
    const std::string type = r.string(r.member(entry, p, "type"), p + "/type");
    const SceneType* st = find_scene_type(type);
    if (st == nullptr) {
      std::string known;
      std::vector<std::string> names_known;
      for (const auto& t : scene_types()) {
        (known += known.empty() ? "" : ", ") += t.name;
        names_known.push_back(t.name);
      }
      std::string near = did_you_mean(type, names_known);
      r.fail(p + "/type", ((("unknown scene type \"" + type) += "\" (known: ") += known) +=
                          ")" + (near.empty() ? near : ";" + near));
    }
    json light = entry.value("light", json::object());
    json camera = entry.value("camera", json::object());
    check_light(r, light, p + "/light");
    check_camera(r, camera, p + "/camera");
    bool infer = true;
    if (entry.contains("infer_receivers")) {
      infer = r.boolean(entry["infer_receivers"], p + "/infer_receivers");
    }
    std::optional<double> max_rmse;
    if (entry.contains("max_rmse")) max_rmse = r.number(entry["max_rmse"], p + "/max_rmse", 0, 1);
    const json given = entry.value("params", json::object());
    const std::string label =
        entry.contains("label") ? r.label(entry["label"], p + "/label") : type;
    for (const json& combo : expand_sweeps(given, file, p + "/params")) {
      SceneVariant v;
      v.type = type;
      v.pointer = p;
      v.params = resolve_sweep_combo(st->params, given, combo, file, p + "/params");
      v.params = resolve_paths(st->params, v.params, file);
      if (st->check) {
        const auto [param, problem] = st->check(v.params);
        if (!problem.empty()) r.fail(swept_pointer(given, combo, p + "/params", param), problem);
      }
      // A labelled entry is not named by the file it reads (unless it sweeps
      // files): its job ids stay when the file is moved or renamed, and its
      // identity is the file's content (config/identity.h).
      json named = combo;
      if (entry.contains("label"))
        for (const ParamSpec& s : st->params)
          if (s.is_path && !(given.contains(s.name) && given[s.name].is_array()))
            named.erase(s.name);
      v.name = variant_name(label, st->params, named);
      for (auto it = given.begin(); it != given.end(); ++it)
        if (it.value().is_array()) v.swept[it.key()] = combo[it.key()];
      v.light = light;
      v.camera = camera;
      v.infer_receivers = infer;
      v.max_rmse = max_rmse;
      if (!names.insert(v.name).second)
        r.fail(p,
               "scene variant \"" + v.name + "\" appears twice; give entries distinct \"label\"s");
      e.scenes.push_back(std::move(v));
    }
  }

  // Techniques.
  const json& techniques = r.member(doc, "", "techniques");
  if (!techniques.is_array() || techniques.empty())
    r.fail("/techniques", "expected a non-empty list of techniques, found " + describe(techniques));
  names.clear();
  for (size_t i = 0; i < techniques.size(); ++i) {
    const std::string p = "/techniques/" + std::to_string(i);
    for (TechniqueVariant& v : technique_variants(r, registry, techniques[i], p, file, true)) {
      if (!names.insert(v.name).second)
        r.fail(p, "technique variant \"" + v.name +
                      "\" appears twice; give entries distinct \"label\"s");
      e.techniques.push_back(std::move(v));
    }
  }

  // Resolutions.
  const json& res = r.member(doc, "", "resolutions");
  if (!res.is_array() || res.empty())
    r.fail("/resolutions", "expected a non-empty list of resolutions, found " + describe(res));
  for (size_t i = 0; i < res.size(); ++i) {
    const std::string p = "/resolutions/" + std::to_string(i);
    const Resolution parsed = parse_resolution(r, res[i], p);
    if (std::find(e.resolutions.begin(), e.resolutions.end(), parsed) != e.resolutions.end())
      r.fail(p, "resolution " + parsed.label() + " appears twice");
    e.resolutions.push_back(parsed);
  }

  // One record file per job: two jobs must never share an id.
  std::map<std::string, std::string> ids;
  for (const auto& sv : e.scenes)
    for (const auto& res_ : e.resolutions)
      for (const auto& tv : e.techniques) {
        const std::string what = sv.name + " @ " + res_.label() + " / " + tv.name;
        const auto [it, fresh] = ids.emplace(job_id(sv.name, res_.label(), tv.name), what);
        if (!fresh)
          r.fail(tv.pointer, "the jobs \"" + it->second + "\" and \"" + what +
                                 "\" would share the job id \"" + it->first + "\"");
      }

  read_config_blocks(r, doc, e);
  // The control: "none" unless the config names another, or null for none.
  const json* control = doc.contains("frames") && doc["frames"].contains("control")
                            ? &doc["frames"]["control"]
                            : nullptr;
  if (control == nullptr && registry.find(kDefaultControl) != nullptr)
    e.control =
        technique_variants(r, registry, json(kDefaultControl), "/frames/control", file, false)
            .front();
  else if (control != nullptr && !control->is_null()) {
    // Every job is timed next to the control: without it none can run.
    auto variants = technique_variants(r, registry, *control, "/frames/control", file, false);
    if (variants.size() != 1)
      r.fail("/frames/control/params",
             "expected one control variant, found a sweep of " + std::to_string(variants.size()));
    e.control = std::move(variants.front());
  }
  return e;
}

Experiment load_experiment(const std::string& path, const Registry& registry,
                           const ExperimentLimits& limits) {
  const std::string text = read_input_file(path, JsonLimits{}.max_bytes, "config file");
  auto positions = std::make_shared<JsonPositions>();
  const json doc = parse_json_text(text, path, {}, 0, positions.get());
  Experiment e;
  try {
    e = parse_experiment(doc, path, registry, limits);
  } catch (const InputError& ex) {
    throw located(ex, path, *positions);
  }
  for (SceneVariant& v : e.scenes) v.position = positions->find(v.pointer);
  e.positions = std::move(positions);
  Hasher h;
  h.add(text);
  e.content_hash = h.hex();
  return e;
}

Scene build_scene(const SceneVariant& v, const std::string& config_file) {
  Scene scene = find_scene_type(v.type)->build(v.params);
  apply_overrides(v, scene);
  scene.name = v.name;
  const std::string problem = scene_setup_problem(scene);
  if (!problem.empty())
    throw InputError(config_file, v.pointer, "scene " + v.name + ": " + problem, v.position);
  return scene;
}

}  // namespace sb::config
