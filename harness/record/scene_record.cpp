#include "record/scene_record.h"

namespace sb {

using json = nlohmann::json;

namespace {

template <size_t N>
json numbers(const std::array<double, N>& v) {
  json out = json::array();
  for (const double x : v) out.push_back(json_number(x));
  return out;
}

template <size_t N>
std::array<double, N> numbers(const Fields& f, const std::string& key) {
  const std::vector<double> v = f.get<std::vector<double>>(key);
  if (v.size() != N) f.fail(key, "expected " + std::to_string(N) + " numbers");
  std::array<double, N> out{};
  for (size_t i = 0; i < N; ++i) out[i] = v[i];
  return out;
}

}  // namespace

json SceneRecord::to_json() const {
  json s = {{"type", type}, {"variant", variant}, {"params", params}};
  if (built) {
    s["triangles"] = built->triangles;
    s["caster_triangles"] = built->caster_triangles;
    s["analytic_casters"] = built->analytic_casters;
    const LightRecord& l = built->light;
    s["light"] = {{"center", numbers(l.center)},
                  {"target", numbers(l.target)},
                  {"size", numbers(l.size)},
                  {"intensity", json_number(l.intensity)}};
    const CameraRecord& c = built->camera;
    s["camera"] = {
        {"eye", numbers(c.eye)}, {"target", numbers(c.target)}, {"fov_y", json_number(c.fov_y)}};
    const DerivedRecord& d = built->derived;
    s["derived"] = {{"closedness_checked", d.closedness_checked},
                    {"adjacency_built", d.adjacency_built},
                    {"receiver_inference", d.receiver_inference},
                    {"inferred_receivers", d.inferred_receivers}};
  }
  return s;
}

SceneRecord SceneRecord::from_json(const Fields& f) {
  SceneRecord s;
  s.type = f.get<std::string>("type");
  s.variant = f.get<std::string>("variant");
  s.params = f.get<json>("params");
  // A built scene has all of these; a scene that failed to build, none.
  if (f.has("triangles") || f.has("caster_triangles") || f.has("light") || f.has("camera") ||
      f.has("derived")) {
    BuiltScene b;
    b.triangles = f.get<std::int64_t>("triangles");
    b.caster_triangles = f.get<std::int64_t>("caster_triangles");
    b.analytic_casters = f.find<std::int64_t>("analytic_casters").value_or(0);  // older records
    const Fields light = f.object("light");
    b.light.center = numbers<3>(light, "center");
    b.light.target = numbers<3>(light, "target");
    b.light.size = numbers<2>(light, "size");
    b.light.intensity = light.get<double>("intensity");
    const Fields camera = f.object("camera");
    b.camera.eye = numbers<3>(camera, "eye");
    b.camera.target = numbers<3>(camera, "target");
    b.camera.fov_y = camera.get<double>("fov_y");
    const Fields derived = f.object("derived");
    b.derived.closedness_checked = derived.get<bool>("closedness_checked");
    b.derived.adjacency_built = derived.get<bool>("adjacency_built");
    b.derived.receiver_inference = derived.get<bool>("receiver_inference");
    b.derived.inferred_receivers = derived.get<std::vector<std::string>>("inferred_receivers");
    s.built = std::move(b);
  }
  return s;
}

json PluginRecord::to_json() const {
  return {{"file", file}, {"size", size}, {"sha256", sha256}, {"api_version", api_version}};
}

PluginRecord PluginRecord::from_json(const Fields& f) {
  PluginRecord p;
  p.file = f.get<std::string>("file");
  p.size = f.get<std::int64_t>("size");
  p.sha256 = f.get<std::string>("sha256");
  p.api_version = f.get<int>("api_version");
  return p;
}

json TechniqueRecord::to_json() const {
  json t = {{"name", name}, {"family", family}, {"variant", variant}, {"params", params}};
  if (plugin) t["plugin"] = plugin->to_json();
  if (gpu_bytes) t["gpu_bytes"] = *gpu_bytes;
  return t;
}

TechniqueRecord TechniqueRecord::from_json(const Fields& f) {
  TechniqueRecord t;
  t.name = f.get<std::string>("name");
  t.family = f.get<std::string>("family");
  t.variant = f.get<std::string>("variant");
  t.params = f.get<json>("params");
  if (const auto p = f.find_object("plugin")) t.plugin = PluginRecord::from_json(*p);
  t.gpu_bytes = f.find<std::int64_t>("gpu_bytes");
  return t;
}

}  // namespace sb
