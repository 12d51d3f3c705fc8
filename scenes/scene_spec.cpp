#include "scenes/scene_spec.h"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/bounded_text.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/scene_types.h"
#include "scenes/receiver_inference.h"
#include "scenes/topology.h"

namespace sb {

using core::AreaLight;
using core::Bounds;
using core::Camera;
using core::find_scene_type;
using core::InputError;
using core::JsonReader;
using core::Mesh;
using core::Params;
using core::resolve_params;
using core::Scene;
using core::scene_types;
using core::SceneType;
using core::to_string;

namespace {

using json = nlohmann::json;
constexpr const char* kFile = "scene spec";

// "3" -> 3, "true" -> true, "models/x.glb" -> "models/x.glb".
json parse_value(const std::string& text) {
  const json v = json::parse(text, nullptr, false);
  return v.is_discarded() || v.is_structured() ? json(text) : v;
}

json parse_short_form(const std::string& spec) {
  const size_t colon = spec.find(':');
  json out = {{"type", spec.substr(0, colon)}, {"params", json::object()}};
  if (colon == std::string::npos) return out;
  const std::string rest = spec.substr(colon + 1);
  size_t start = 0;
  while (start <= rest.size()) {
    const size_t stop = std::min(rest.find(',', start), rest.size());
    const std::string item = rest.substr(start, stop - start);
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(kFile, "", "expected NAME=VALUE after ':', found '" + item + "'");
    out["params"][item.substr(0, eq)] = parse_value(item.substr(eq + 1));
    start = stop + 1;
  }
  return out;
}

}  // namespace

Scene build_scene_from_spec(const std::string& spec) {
  // Text from a command line may be any bytes; the messages below quote it
  // (found by tests/fuzz/fuzz_scene_spec).
  try {
    (void)json(spec).dump();
  } catch (const json::type_error& e) {
    const std::string what = e.what();
    const size_t bracket = what.find("] ");
    throw InputError(
        kFile, "",
        "not UTF-8 text: " + (bracket == std::string::npos ? what : what.substr(bracket + 2)));
  }
  json doc;
  if (!spec.empty() && spec[0] == '{') {
    doc = json::parse(spec, nullptr, false);
    if (doc.is_discarded() || !doc.is_object())
      throw InputError(kFile, "", "expected a JSON object {\"type\": ..., \"params\": {...}}");
    JsonReader([](const std::string& pointer, const std::string& problem) {
      throw InputError(kFile, pointer, problem);
    }).only_keys(doc, "", {"type", "params"});
  } else {
    doc = parse_short_form(spec);
  }
  const json type = doc.value("type", json());
  if (!type.is_string() || type.get<std::string>().empty())
    throw InputError(kFile, "/type", "expected a scene type name");
  const SceneType* t = find_scene_type(type.get<std::string>());
  if (t == nullptr) {
    std::string known;
    for (const auto& s : scene_types()) known += (known.empty() ? "" : ", ") + s.name;
    throw InputError(kFile, "/type",
                     "unknown scene type '" + type.get<std::string>() + "' (known: " + known + ")");
  }
  Params params = resolve_params(t->params, doc.value("params", json::object()), kFile, "/params");
  if (t->check) {
    const auto [param, problem] = t->check(params);
    if (!problem.empty()) throw InputError(kFile, "/params/" + param, problem);
  }
  json values = params.json();
  for (const auto& s : t->params)
    if (s.is_path)
      values[s.name] =
          std::filesystem::absolute(values[s.name].get<std::string>()).lexically_normal().string();
  Scene scene = t->build(Params(std::move(values)));
  if (scene.name.empty()) scene.name = t->name;
  return scene;
}

std::string describe_scene(const Scene& s) {
  std::string out;
  char line[1024];  // names cut to 60 characters, at most 8 bytes each escaped
  const auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    out += line;
  };
  size_t closed = 0, inferred = 0;
  std::string meshes;
  const ShadowNothingTest shadows_nothing(s);
  for (size_t i = 0; i < s.meshes.size(); ++i) {
    const Mesh& m = s.meshes[i];
    const MeshTopology t = analyse_topology(m);
    closed += t.closed() ? 1 : 0;
    const bool infer = m.casts_shadow && shadows_nothing(i);
    inferred += infer ? 1 : 0;
    std::snprintf(
        line, sizeof line, "  %-24s %9zu tris  %-8s %-6s %s%s%s\n",
        core::bounded_text(m.name, 60).c_str(), m.triangle_count(),
        infer            ? "inferred"
        : m.casts_shadow ? "caster"
                         : "receiver",
        t.closed() ? "closed" : "open", m.alpha_tested() ? "alpha-mask " : "",
        m.double_sided ? "double-sided " : "",
        m.analytic.has() ? (std::string("analytic-") + to_string(m.analytic.kind)).c_str() : "");
    meshes += line;
  }
  const Bounds b = s.bounds();
  add("scene %s: %zu meshes (%zu closed), %zu triangles (%zu casting), %zu textures\n",
      core::bounded_text(s.name, 60).c_str(), s.meshes.size(), closed, s.triangle_count(),
      s.caster_triangle_count(), s.textures.size());
  add("bounds: [%g %g %g] - [%g %g %g]\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
  const AreaLight& l = s.light;
  add("light: center [%g %g %g] target [%g %g %g] size %g x %g intensity %g\n", l.center.x,
      l.center.y, l.center.z, l.target.x, l.target.y, l.target.z, l.width(), l.height(),
      l.intensity);
  const Camera& c = s.camera;
  add("camera: eye [%g %g %g] target [%g %g %g] fov_y %g near %g far %g\n", c.eye.x, c.eye.y,
      c.eye.z, c.target.x, c.target.y, c.target.z, c.fov_y_degrees, c.near_plane, c.far_plane);
  out += "meshes:\n" + meshes;
  if (inferred > 0)
    out +=
        "inferred: casts in the file but can shadow nothing; a run makes it a receiver "
        "(\"infer_receivers\": false keeps it a caster)\n";
  return out;
}

}  // namespace sb
