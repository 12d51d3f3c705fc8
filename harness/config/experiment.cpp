#include "config/experiment.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/json_file.h"
#include "config/unknown_technique.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/names.h"
#include "core/nearest_names.h"
#include "core/scene_setup_check.h"
#include "reference/adaptive.h"
#include "reference/embree_isa.h"

namespace sb {
namespace {

using json = nlohmann::json;

std::string describe(const json& v) {
  std::string d = v.dump();
  if (d.size() > 60) d = d.substr(0, 57) + "...";
  return std::string(v.type_name()) + " " + d;
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw InputError(file_, pointer.empty() ? "/" : pointer, what);
  }
  const json& object(const json& v, const std::string& pointer, const std::string& what) const {
    if (!v.is_object()) fail(pointer, "expected " + what + " (an object), found " + describe(v));
    return v;
  }
  void only_keys(const json& obj, const std::string& pointer,
                 const std::vector<std::string>& allowed) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool ok = false;
      for (const auto& a : allowed) ok = ok || a == it.key();
      if (!ok) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(pointer + "/" + it.key(),
             "unknown key '" + it.key() + "' (expected one of: " + list + ")");
      }
    }
  }
  int integer(const json& v, const std::string& pointer, long long lo, long long hi) const {
    if (!v.is_number_integer()) fail(pointer, "expected an integer, found " + describe(v));
    const auto i = v.get<long long>();
    if (i < lo || i > hi)
      fail(pointer, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                        "], found " + v.dump());
    return static_cast<int>(i);
  }
  std::string string(const json& v, const std::string& pointer) const {
    if (!v.is_string()) fail(pointer, "expected a string, found " + describe(v));
    return v.get<std::string>();
  }
  // A label names variants in tables and charts: short, printable.
  std::string label(const json& v, const std::string& pointer) const {
    std::string s = string(v, pointer);
    if (s.empty() || s.size() > 200)
      fail(pointer, "expected a label of 1 to 200 bytes, found " + std::to_string(s.size()));
    for (char c : s)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        fail(pointer, "expected a label without control characters, found " + describe(v));
    return s;
  }
  double number(const json& v, const std::string& pointer, double lo, double hi) const {
    if (!v.is_number()) fail(pointer, "expected a number, found " + describe(v));
    const double d = v.get<double>();
    if (!(d >= lo && d <= hi))
      fail(pointer, "expected a number in [" + json(lo).dump() + ", " + json(hi).dump() +
                        "], found " + v.dump());
    return d;
  }
  bool boolean(const json& v, const std::string& pointer) const {
    if (!v.is_boolean()) fail(pointer, "expected true or false, found " + describe(v));
    return v.get<bool>();
  }
  glm::vec3 vec3(const json& v, const std::string& pointer) const {
    if (!v.is_array() || v.size() != 3)
      fail(pointer, "expected an array of 3 numbers, found " + describe(v));
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      if (!v[size_t(i)].is_number())
        fail(pointer + "/" + std::to_string(i),
             "expected a number, found " + describe(v[size_t(i)]));
      out[i] = v[size_t(i)].get<float>();
    }
    return out;
  }
  // A point or direction: finite as a float, and within what can be traced.
  glm::vec3 coordinates(const json& v, const std::string& pointer) const {
    const glm::vec3 out = vec3(v, pointer);
    for (int i = 0; i < 3; ++i)
      if (!(std::fabs(out[i]) <= kLargestCoordinate))
        fail(pointer + "/" + std::to_string(i),
             "expected a coordinate within ±1e15, found " + describe(v[size_t(i)]));
    return out;
  }
  float positive(const json& v, const std::string& pointer, bool allow_zero) const {
    if (!v.is_number()) fail(pointer, "expected a number, found " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(static_cast<float>(d)))
      fail(pointer, "expected a number within float range, found " + v.dump());
    if (allow_zero ? d < 0.0 : d <= 0.0)
      fail(pointer, std::string("expected a ") + (allow_zero ? "non-negative" : "positive") +
                        " number, found " + v.dump());
    return static_cast<float>(d);
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

std::string value_label(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// "base/k=5,size=1024" from the explicitly given parameters, in declaration order.
std::string variant_name(const std::string& base, const std::vector<ParamSpec>& specs,
                         const json& given) {
  std::string suffix;
  for (const auto& s : specs)
    if (given.contains(s.name))
      suffix += (suffix.empty() ? "" : ",") + s.name + "=" + value_label(given.at(s.name));
  return suffix.empty() ? base : base + "/" + suffix;
}

void check_light(const Reader& r, const json& light, const std::string& p) {
  r.object(light, p, "a light override");
  r.only_keys(light, p, {"center", "target", "size", "intensity"});
  if (light.contains("center")) r.coordinates(light["center"], p + "/center");
  if (light.contains("target")) r.coordinates(light["target"], p + "/target");
  if (light.contains("intensity")) r.positive(light["intensity"], p + "/intensity", true);
  if (light.contains("size")) {
    const json& s = light["size"];
    if (s.is_number()) {
      r.positive(s, p + "/size", true);
    } else if (s.is_array() && s.size() == 2) {
      r.positive(s[0], p + "/size/0", true);
      r.positive(s[1], p + "/size/1", true);
    } else {
      r.fail(p + "/size", "expected a number or [width, height], found " + describe(s));
    }
  }
  if (light.contains("center") && light.contains("target") &&
      r.vec3(light["center"], p + "/center") == r.vec3(light["target"], p + "/target"))
    r.fail(p + "/target", "expected a target different from the light's center");
}

void check_camera(const Reader& r, const json& camera, const std::string& p) {
  r.object(camera, p, "a camera override");
  r.only_keys(camera, p, {"eye", "target", "up", "fov_y", "near", "far"});
  for (const char* k : {"eye", "target", "up"})
    if (camera.contains(k)) r.coordinates(camera[k], p + "/" + k);
  if (camera.contains("fov_y")) {
    const float f = r.positive(camera["fov_y"], p + "/fov_y", false);
    if (!(f >= 1e-3f && f < 180.0f))
      r.fail(p + "/fov_y", "expected degrees in [0.001, 180), found " + camera["fov_y"].dump());
  }
  if (camera.contains("near")) r.positive(camera["near"], p + "/near", false);
  if (camera.contains("far")) r.positive(camera["far"], p + "/far", false);
  // What the overrides alone can tell; the built scene's camera is checked
  // again whole (core/scene_setup_check.h).
  if (camera.contains("near") && camera.contains("far") &&
      !(camera["far"].get<double>() > camera["near"].get<double>()))
    r.fail(p + "/far", "expected far greater than near (" + camera["near"].dump() + "), found " +
                           camera["far"].dump());
  if (camera.contains("up") && r.vec3(camera["up"], p + "/up") == glm::vec3(0.0f))
    r.fail(p + "/up", "expected a non-zero up vector");
  if (camera.contains("eye") && camera.contains("target")) {
    Camera c;
    c.eye = r.vec3(camera["eye"], p + "/eye");
    c.target = r.vec3(camera["target"], p + "/target");
    if (camera.contains("up")) c.up = r.vec3(camera["up"], p + "/up");
    const std::string problem = camera_problem(c);
    if (!problem.empty()) r.fail(p + (camera.contains("up") ? "" : "/target"), problem);
  }
}

constexpr uint64_t kMaxPixels = uint64_t(1) << 24;

Resolution parse_resolution(const Reader& r, const json& v, const std::string& p) {
  Resolution res;
  if (v.is_array() && v.size() == 2) {
    res.width = r.integer(v[0], p + "/0", 1, 16384);
    res.height = r.integer(v[1], p + "/1", 1, 16384);
  } else if (v.is_string()) {
    const std::string s = v.get<std::string>();
    const auto x = s.find('x');
    try {
      size_t used = 0;
      res.width = std::stoi(s.substr(0, x), &used);
      if (x == std::string::npos || used != x) throw std::invalid_argument(s);
      res.height = std::stoi(s.substr(x + 1), &used);
      if (used != s.size() - x - 1) throw std::invalid_argument(s);
    } catch (const std::exception&) {
      r.fail(p, "expected \"WIDTHxHEIGHT\" or [width, height], found " + v.dump());
    }
    if (res.width < 1 || res.height < 1 || res.width > 16384 || res.height > 16384)
      r.fail(p, "expected sizes in [1, 16384], found " + v.dump());
  } else {
    r.fail(p, "expected \"WIDTHxHEIGHT\" or [width, height], found " + describe(v));
  }
  // Every pixel costs the G-buffer, the reference and the images about 100 bytes.
  if (uint64_t(res.width) * uint64_t(res.height) > kMaxPixels)
    r.fail(p, "expected at most " + std::to_string(kMaxPixels) + " pixels (4096x4096), found " +
                  res.label());
  return res;
}

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

// How many variants an entry's parameters sweep to (the product of its
// lists' lengths), saturating instead of overflowing; malformed parameters
// count as one (expand_sweeps reports them).
uint64_t sweep_count(const json& params) {
  uint64_t n = 1;
  if (!params.is_object()) return n;
  for (const auto& v : params) {
    const uint64_t k = v.is_array() ? std::max<uint64_t>(v.size(), 1) : 1;
    n = n > UINT64_MAX / k ? UINT64_MAX : n * k;
  }
  return n;
}

uint64_t saturating_mul(uint64_t a, uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

// Jobs = scene variants × technique variants × resolutions, from the lists'
// lengths alone: a sweep too big to run is refused before it is expanded.
void check_job_count(const Reader& r, const json& doc, const ExperimentLimits& limits) {
  uint64_t scenes = 0, techniques = 0, resolutions = 1;
  std::string biggest;  // the entry with the most variants, for the message
  uint64_t biggest_n = 0;
  const auto count = [&](const char* list, uint64_t& total) {
    if (!doc.contains(list) || !doc[list].is_array()) return;
    for (size_t i = 0; i < doc[list].size(); ++i) {
      const json& entry = doc[list][i];
      const uint64_t n =
          entry.is_object() && entry.contains("params") ? sweep_count(entry["params"]) : 1;
      total = total > UINT64_MAX - n ? UINT64_MAX : total + n;
      if (n > biggest_n) {
        biggest_n = n;
        biggest = std::string("/") + list + "/" + std::to_string(i) + "/params";
      }
    }
  };
  count("scenes", scenes);
  count("techniques", techniques);
  if (doc.contains("resolutions") && doc["resolutions"].is_array())
    resolutions = std::max<uint64_t>(doc["resolutions"].size(), 1);
  const uint64_t jobs = saturating_mul(saturating_mul(scenes, techniques), resolutions);
  if (jobs > limits.max_jobs)
    r.fail(biggest.empty() ? "/" : biggest,
           "the experiment has " +
               (jobs == UINT64_MAX ? std::string("more than 2^64") : std::to_string(jobs)) +
               " jobs (" + std::to_string(scenes) + " scene variants × " +
               std::to_string(techniques) + " technique variants × " + std::to_string(resolutions) +
               " resolutions), over the limit of " + std::to_string(limits.max_jobs) +
               "; raise it with --max-jobs");
}

}  // namespace

std::vector<json> expand_sweeps(const json& params, const std::string& file,
                                const std::string& pointer) {
  std::vector<json> out{json::object()};
  if (params.is_null()) return out;
  if (!params.is_object())
    throw InputError(file, pointer, "expected an object of parameters, found " + describe(params));
  // Counted before anything is expanded.
  if (sweep_count(params) > 100000)
    throw InputError(file, pointer, "the sweep expands to more than 100000 variants");
  for (auto it = params.begin(); it != params.end(); ++it) {
    std::vector<json> values;
    if (it.value().is_array()) {
      if (it.value().empty())
        throw InputError(file, pointer + "/" + it.key(),
                         "expected a non-empty list to sweep, found []");
      for (const auto& v : it.value()) values.push_back(v);
    } else {
      values.push_back(it.value());
    }
    std::vector<json> next;
    for (const auto& partial : out)
      for (const auto& v : values) {
        json p = partial;
        p[it.key()] = v;
        next.push_back(std::move(p));
      }
    out = std::move(next);
  }
  return out;
}

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

// The variants of one technique entry: a name, or {"name", "params", "label"}
// whose list-valued params sweep.
std::vector<TechniqueVariant> technique_variants(const Reader& r, const Registry& registry,
                                                 const json& given_entry, const std::string& p,
                                                 const std::string& file, bool may_be_unavailable) {
  json entry = given_entry;
  if (entry.is_string()) entry = json{{"name", entry}};
  r.object(entry, p, "a technique (a name or an object)");
  r.only_keys(entry, p, {"name", "params", "label", "own_map_size"});
  if (!entry.contains("name")) r.fail(p + "/name", "expected a technique name, found nothing");
  const bool own_map_size =
      entry.contains("own_map_size") && r.boolean(entry["own_map_size"], p + "/own_map_size");
  const std::string name = r.string(entry["name"], p + "/name");
  const TechniqueInfo* info = registry.find(name);
  const std::string label = entry.contains("label") ? r.label(entry["label"], p + "/label") : name;
  const json params = entry.value("params", json::object());
  std::vector<TechniqueVariant> out;
  if (info == nullptr) {
    const UnknownTechnique unknown = unknown_technique(name, registry);
    if (!unknown.plugin_failed || !may_be_unavailable)
      r.fail(p + (given_entry.is_string() ? "" : "/name"), unknown.message);
    // Perhaps the failed plugin's: its jobs fail, the others run.
    return unavailable_variants(name, label, params, p, unknown.message, file);
  }
  for (const json& combo : expand_sweeps(params, file, p + "/params")) {
    TechniqueVariant v;
    v.info = info;
    v.pointer = p;
    v.params = resolve_params(info->params, combo, file, p + "/params");
    if (info->check) {
      const auto [param, problem] = info->check(v.params);
      if (!problem.empty()) r.fail(p + "/params/" += param, problem);
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
  Reader r(file);
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
  if (!doc.contains("scenes")) r.fail("/scenes", "expected a list of scenes, found nothing");
  const json& scenes = doc["scenes"];
  if (!scenes.is_array() || scenes.empty())
    r.fail("/scenes", "expected a non-empty list of scenes, found " + describe(scenes));
  std::set<std::string> names;
  for (size_t i = 0; i < scenes.size(); ++i) {
    const std::string p = "/scenes/" + std::to_string(i);
    const json& entry = r.object(scenes[i], p, "a scene");
    r.only_keys(entry, p,
                {"type", "params", "light", "camera", "label", "infer_receivers", "max_rmse"});
    if (!entry.contains("type")) r.fail(p + "/type", "expected a scene type, found nothing");
    const std::string type = r.string(entry["type"], p + "/type");
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
      if (!entry["infer_receivers"].is_boolean())
        r.fail(p + "/infer_receivers",
               "expected true or false, found " + describe(entry["infer_receivers"]));
      infer = entry["infer_receivers"].get<bool>();
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
      v.params = resolve_params(st->params, combo, file, p + "/params");
      v.params = resolve_paths(st->params, v.params, file);
      if (st->check) {
        const auto [param, problem] = st->check(v.params);
        if (!problem.empty()) r.fail(p + "/params/" += param, problem);
      }
      v.name = variant_name(label, st->params, combo);
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
  if (!doc.contains("techniques"))
    r.fail("/techniques", "expected a list of techniques, found nothing");
  const json& techniques = doc["techniques"];
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
  if (!doc.contains("resolutions"))
    r.fail("/resolutions", "expected a list of resolutions, found nothing");
  const json& res = doc["resolutions"];
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

  if (doc.contains("frames")) {
    const json& f = r.object(doc["frames"], "/frames", "frame counts");
    r.only_keys(f, "/frames", {"warmup", "timed", "control"});
    if (f.contains("warmup")) e.warmup_frames = r.integer(f["warmup"], "/frames/warmup", 0, 100000);
    if (f.contains("timed")) e.timed_frames = r.integer(f["timed"], "/frames/timed", 1, 100000);
  }
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
  if (doc.contains("reference")) {
    const json& ref = r.object(doc["reference"], "/reference", "reference settings");
    r.only_keys(ref, "/reference",
                {"method", "second_method", "spp", "seed", "cache", "embree_config", "adaptive",
                 "pilot_spp", "target_std_error"});
    // true for "exact", false for "monte_carlo".
    const auto is_exact = [&](const char* key) {
      const std::string pointer = std::string("/reference/") + key;
      const std::string method = r.string(ref[key], pointer);
      if (method != "monte_carlo" && method != "exact")
        r.fail(pointer, "expected \"monte_carlo\" or \"exact\", found \"" + method + "\"");
      return method == "exact";
    };
    if (ref.contains("method")) e.reference.settings.exact = is_exact("method");
    if (ref.contains("second_method")) {
      e.reference.second_exact = is_exact("second_method");
      if (*e.reference.second_exact == e.reference.settings.exact)
        r.fail("/reference/second_method",
               std::string("expected the other method than /reference/method (") +
                   (e.reference.settings.exact ? "exact" : "monte_carlo") + "), found the same");
    }
    if (ref.contains("spp"))
      e.reference.settings.spp = r.integer(ref["spp"], "/reference/spp", 1, 1 << 20);
    if (ref.contains("seed"))
      e.reference.settings.seed =
          static_cast<uint64_t>(r.integer(ref["seed"], "/reference/seed", 0, 2147483647));
    if (ref.contains("cache")) e.reference.cache = r.boolean(ref["cache"], "/reference/cache");
    if (ref.contains("adaptive"))
      e.reference.settings.adaptive = r.boolean(ref["adaptive"], "/reference/adaptive");
    if (ref.contains("pilot_spp"))
      e.reference.settings.pilot_spp =
          r.integer(ref["pilot_spp"], "/reference/pilot_spp", 1, 1 << 20);
    if (ref.contains("target_std_error"))
      e.reference.settings.target_std_error =
          r.number(ref["target_std_error"], "/reference/target_std_error", 1e-6, 0.5);
    if (e.reference.settings.adaptive) {
      // Whether the counts nest is the config's question, not the run's.
      const int pilot = e.reference.settings.pilot_spp;
      if (pilot != 4 && pilot != 16 && pilot != 64)
        r.fail(ref.contains("pilot_spp") ? "/reference/pilot_spp" : "/reference/adaptive",
               reference::detail::adaptive_layout_problem(e.reference.settings.spp, pilot));
      else if (const std::string why =
                   reference::detail::adaptive_layout_problem(e.reference.settings.spp, pilot);
               !why.empty())
        r.fail("/reference/spp", "with /reference/adaptive: " + why);
    }
    if (ref.contains("embree_config")) {
      e.reference.settings.embree_config =
          r.string(ref["embree_config"], "/reference/embree_config");
      try {  // syntax only: whether this CPU has the ISA is the run's question
        reference::check_embree_config(e.reference.settings.embree_config);
      } catch (const std::invalid_argument& ex) {
        r.fail("/reference/embree_config", ex.what());
      }
    }
  }
  if (doc.contains("stability")) {
    const json& st = r.object(doc["stability"], "/stability", "stability settings");
    r.only_keys(st, "/stability",
                {"flicker_frames", "flicker_step", "flicker_factor", "sensitivity",
                 "sensitivity_step", "stiff_threshold", "max_rmse"});
    StabilityConfig c;
    if (st.contains("flicker_frames")) {
      c.flicker_frames = r.integer(st["flicker_frames"], "/stability/flicker_frames", 0, 64);
      if (c.flicker_frames == 1)
        r.fail("/stability/flicker_frames", "expected 0 (off) or at least 2 frames, found 1");
    }
    if (st.contains("flicker_step"))
      c.flicker_step = r.number(st["flicker_step"], "/stability/flicker_step", 0, 0.1);
    if (st.contains("flicker_factor"))
      c.flicker_factor = r.number(st["flicker_factor"], "/stability/flicker_factor", 1, 1e6);
    if (st.contains("sensitivity"))
      c.sensitivity = r.boolean(st["sensitivity"], "/stability/sensitivity");
    if (st.contains("sensitivity_step"))
      c.sensitivity_step =
          r.number(st["sensitivity_step"], "/stability/sensitivity_step", 1e-6, 0.5);
    if (st.contains("stiff_threshold"))
      c.stiff_threshold = r.number(st["stiff_threshold"], "/stability/stiff_threshold", 0, 1e6);
    if (st.contains("max_rmse")) c.max_rmse = r.number(st["max_rmse"], "/stability/max_rmse", 0, 1);
    e.stability = c;
  }
  if (doc.contains("metrics")) {
    const json& m = r.object(doc["metrics"], "/metrics", "metric settings");
    r.only_keys(m, "/metrics", {"distance_thirds"});
    if (m.contains("distance_thirds"))
      e.distance_thirds = r.boolean(m["distance_thirds"], "/metrics/distance_thirds");
  }
  if (doc.contains("limits")) {
    const json& l = r.object(doc["limits"], "/limits", "time limits");
    r.only_keys(l, "/limits", {"job_seconds", "setup_seconds"});
    // Below a second a busy machine kills healthy jobs; a week is no limit.
    if (l.contains("job_seconds"))
      e.limits.job_seconds = r.number(l["job_seconds"], "/limits/job_seconds", 1, 604800);
    if (l.contains("setup_seconds"))
      e.limits.setup_seconds = r.number(l["setup_seconds"], "/limits/setup_seconds", 1, 604800);
  }
  return e;
}

Experiment load_experiment(const std::string& path, const Registry& registry,
                           const ExperimentLimits& limits) {
  const std::string text = read_input_file(path, JsonLimits{}.max_bytes, "config file");
  Experiment e = parse_experiment(parse_json_text(text, path), path, registry, limits);
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
    throw InputError(config_file, v.pointer, "scene " + v.name + ": " + problem);
  return scene;
}

void apply_overrides(const SceneVariant& v, Scene& scene) {
  AreaLight& l = scene.light;
  const json& light = v.light;
  if (!light.empty()) {
    const auto vec = [](const json& a) {
      return glm::vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
    };
    const glm::vec3 center = light.contains("center") ? vec(light["center"]) : l.center;
    const glm::vec3 target = light.contains("target") ? vec(light["target"]) : l.target;
    float w = l.width(), h = l.height();
    if (light.contains("size")) {
      if (light["size"].is_number()) {
        w = h = light["size"].get<float>();
      } else {
        w = light["size"][0].get<float>();
        h = light["size"][1].get<float>();
      }
    }
    const float intensity = light.value("intensity", l.intensity);
    l = make_area_light(center, target, w, h, intensity);
  }
  const json& cam = v.camera;
  const auto vec = [](const json& a) {
    return glm::vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
  };
  if (cam.contains("eye")) scene.camera.eye = vec(cam["eye"]);
  if (cam.contains("target")) scene.camera.target = vec(cam["target"]);
  if (cam.contains("up")) scene.camera.up = vec(cam["up"]);
  if (cam.contains("fov_y")) scene.camera.fov_y_degrees = cam["fov_y"].get<float>();
  // A moved camera keeps the scene in its depth range, unless told otherwise.
  if (cam.contains("eye") || cam.contains("target")) fit_clip_planes(scene.camera, scene.bounds());
  if (cam.contains("near")) scene.camera.near_plane = cam["near"].get<float>();
  if (cam.contains("far")) scene.camera.far_plane = cam["far"].get<float>();
}

}  // namespace sb
