#include "scenes/gltf_export.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <tuple>

#include "core/atomic_file.h"
#include "core/bounded_text.h"
#include "core/image_codec.h"

namespace sb {

using core::AlphaMode;
using core::AreaLight;
using core::Camera;
using core::Mesh;
using core::Scene;
using core::TextureImage;
using core::write_file_atomically;

namespace {

using json = nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kNearest = 9728;
constexpr int kRepeat = 10497;

json vec(const glm::vec3& v) { return json::array({double(v.x), double(v.y), double(v.z)}); }

std::vector<unsigned char> encode_png(const TextureImage& t) {
  if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4)
    throw std::invalid_argument("texture " + core::quoted_text(t.name) +
                                ": size does not match its pixels");
  const core::Image8 img{t.width, t.height, 4, t.rgba};
  std::vector<unsigned char> out;
  if (const std::string err = core::image_codec().encode_png(img, out); !err.empty())
    throw std::runtime_error("cannot encode texture " + core::quoted_text(t.name) +
                             " as PNG: " + err);
  return out;
}

// Rotation taking glTF's local axes (x, y, -z forward) to (right, up, forward), as [x, y, z, w].
json rotation(const glm::dvec3& right, const glm::dvec3& up, const glm::dvec3& forward) {
  const glm::dquat q = glm::normalize(glm::quat_cast(glm::dmat3(right, up, -forward)));
  return json::array({q.x, q.y, q.z, q.w});
}

// Any unit vector perpendicular to `dir` (dir is unit).
glm::dvec3 perpendicular(const glm::dvec3& dir) {
  const glm::dvec3 up = std::fabs(dir.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  return glm::normalize(glm::cross(dir, up));
}

class GlbWriter {
 public:
  explicit GlbWriter(const Scene& scene) : scene_(scene) {}

  std::vector<uint8_t> write() {
    doc_["asset"] = {{"version", "2.0"}, {"generator", "shadowbench"}};
    doc_["extensionsUsed"] = json::array({"KHR_lights_punctual"});
    json roots = json::array();
    write_textures();
    for (const Mesh& m : scene_.meshes) {
      if (m.positions.empty() || m.indices.size() < 3) continue;  // glTF has no empty meshes
      roots.push_back(int(nodes().size()));
      write_mesh(m);
    }
    roots.push_back(int(nodes().size()));
    write_camera();
    roots.push_back(int(nodes().size()));
    write_light();
    doc_["scene"] = 0;
    doc_["scenes"] =
        json::array({{{"name", scene_.name.empty() ? "scene" : scene_.name},
                      {"nodes", roots},
                      {"extras", {{"shadowbench_scene", {{"ambient", vec(scene_.ambient)}}}}}}});
    if (!bin_.empty()) doc_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    return assemble();
  }

 private:
  json& nodes() {
    if (!doc_.contains("nodes")) doc_["nodes"] = json::array();
    return doc_["nodes"];
  }
  json& array(const char* key) {
    if (!doc_.contains(key)) doc_[key] = json::array();
    return doc_[key];
  }

  int add_view(const void* data, size_t bytes, int target) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);  // every view starts 4-aligned
    const size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    std::memcpy(bin_.data() + offset, data, bytes);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (target != 0) v["target"] = target;
    array("bufferViews").push_back(v);
    return int(array("bufferViews").size() - 1);
  }

  int add_accessor(const void* data, size_t count, size_t element, int ctype, const char* type,
                   int target, const json& min = nullptr, const json& max = nullptr) {
    json a = {{"bufferView", add_view(data, count * element, target)},
              {"componentType", ctype},
              {"count", count},
              {"type", type}};
    if (!min.is_null()) a["min"] = min;
    if (!max.is_null()) a["max"] = max;
    array("accessors").push_back(a);
    return int(array("accessors").size() - 1);
  }

  void write_textures() {
    if (scene_.textures.empty()) return;
    doc_["samplers"] = json::array({{{"magFilter", kNearest},
                                     {"minFilter", kNearest},
                                     {"wrapS", kRepeat},
                                     {"wrapT", kRepeat}}});
    for (size_t i = 0; i < scene_.textures.size(); ++i) {
      const TextureImage& t = scene_.textures[i];
      const std::vector<unsigned char> png = encode_png(t);
      json image = {{"bufferView", add_view(png.data(), png.size(), 0)}, {"mimeType", "image/png"}};
      if (!t.name.empty()) image["name"] = t.name;
      array("images").push_back(image);
      array("textures").push_back({{"sampler", 0}, {"source", i}});
    }
  }

  int material(const Mesh& m) {
    const glm::vec3 c = glm::clamp(m.albedo, glm::vec3(0.0f), glm::vec3(1.0f));
    const int texture =
        m.base_color_texture >= 0 && size_t(m.base_color_texture) < scene_.textures.size()
            ? m.base_color_texture
            : -1;
    const bool mask = m.alpha_mode == AlphaMode::Mask;
    const auto key =
        std::make_tuple(c.x, c.y, c.z, texture, mask, mask ? m.alpha_cutoff : 0.0f, m.double_sided);
    const auto found = materials_.find(key);
    if (found != materials_.end()) return found->second;
    json pbr = {{"baseColorFactor", {double(c.x), double(c.y), double(c.z), 1.0}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", 1.0}};
    if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}};
    json mat = {{"name", "material_" + std::to_string(materials_.size())},
                {"pbrMetallicRoughness", pbr}};
    if (mask) {
      mat["alphaMode"] = "MASK";
      mat["alphaCutoff"] = double(m.alpha_cutoff);
    }
    if (m.double_sided) mat["doubleSided"] = true;
    array("materials").push_back(mat);
    const int index = int(array("materials").size() - 1);
    materials_[key] = index;
    return index;
  }

  void write_mesh(const Mesh& m) {
    const size_t n = m.positions.size();
    for (uint32_t i : m.indices)
      if (i >= n)
        throw std::invalid_argument("mesh " + core::quoted_text(m.name) + ": index " +
                                    std::to_string(i) + " is out of range (" + std::to_string(n) +
                                    " vertices)");
    glm::vec3 lo = m.positions[0], hi = m.positions[0];
    for (const auto& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    json attributes;
    attributes["POSITION"] =
        add_accessor(m.positions.data(), n, 12, kFloat, "VEC3", kArrayBuffer, vec(lo), vec(hi));
    if (m.normals.size() == n) {
      // glTF normals are unit length; zero ones (degenerate input) become +y.
      std::vector<glm::vec3> normals(n);
      for (size_t i = 0; i < n; ++i) {
        const float len = glm::length(m.normals[i]);
        normals[i] = len > 0 && std::isfinite(len) ? m.normals[i] / len : glm::vec3(0, 1, 0);
      }
      attributes["NORMAL"] = add_accessor(normals.data(), n, 12, kFloat, "VEC3", kArrayBuffer);
    }
    if (m.uvs.size() == n)
      attributes["TEXCOORD_0"] = add_accessor(m.uvs.data(), n, 8, kFloat, "VEC2", kArrayBuffer);
    const size_t count = m.indices.size() / 3 * 3;
    const int indices =
        add_accessor(m.indices.data(), count, 4, kUnsignedInt, "SCALAR", kElementArrayBuffer);
    json mesh = {{"name", m.name},
                 {"primitives",
                  {{{"attributes", attributes},
                    {"indices", indices},
                    {"material", material(m)},
                    {"mode", 4}}}}};
    if (!m.casts_shadow) mesh["extras"] = {{"shadowbench_mesh", {{"casts_shadow", false}}}};
    array("meshes").push_back(mesh);
    nodes().push_back({{"name", m.name}, {"mesh", array("meshes").size() - 1}});
  }

  void write_camera() {
    const Camera& c = scene_.camera;
    const glm::dvec3 eye(c.eye);
    glm::dvec3 forward = glm::dvec3(c.target) - eye;
    const double distance = glm::length(forward);
    forward = distance > 0 ? forward / distance : glm::dvec3(0, 0, -1);
    glm::dvec3 right = glm::cross(forward, glm::dvec3(c.up));
    right = glm::length(right) > 1e-12 ? glm::normalize(right) : perpendicular(forward);
    const glm::dvec3 up = glm::cross(right, forward);
    json perspective = {{"yfov", glm::radians(double(c.fov_y_degrees))},
                        {"znear", double(c.near_plane)},
                        {"zfar", double(c.far_plane)}};
    doc_["cameras"] = json::array({{{"type", "perspective"}, {"perspective", perspective}}});
    json node = {{"name", "camera"},
                 {"camera", 0},
                 {"translation", vec(c.eye)},
                 {"rotation", rotation(right, up, forward)}};
    if (distance > 0) node["extras"] = {{"shadowbench_camera", {{"target_distance", distance}}}};
    nodes().push_back(node);
  }

  void write_light() {
    const AreaLight& l = scene_.light;
    const glm::dvec3 center(l.center);
    glm::dvec3 dir = glm::dvec3(l.target) - center;
    const double distance = glm::length(dir);
    dir = distance > 0 ? dir / distance : glm::dvec3(0, -1, 0);
    // The node's x axis spans the rectangle's width, y its height.
    glm::dvec3 u = glm::dvec3(l.half_u) - dir * glm::dot(glm::dvec3(l.half_u), dir);
    u = glm::length(u) > 1e-12 ? glm::normalize(u) : perpendicular(dir);
    const glm::dvec3 v = glm::normalize(glm::cross(u, dir));
    json light = {{"name", "area_light"},
                  {"type", "spot"},
                  {"color", {1.0, 1.0, 1.0}},
                  {"intensity", double(l.intensity)},
                  {"spot", {{"innerConeAngle", 0.0}, {"outerConeAngle", std::numbers::pi / 4}}}};
    json extras = {{"size", {double(l.width()), double(l.height())}},
                   {"intensity", double(l.intensity)}};
    if (distance > 0) extras["target_distance"] = distance;
    // The sun: a directional light (whose place glTF ignores) with its size.
    if (l.is_sun()) {
      light = {{"name", "sun"},
               {"type", "directional"},
               {"color", {1.0, 1.0, 1.0}},
               {"intensity", double(l.intensity)}};
      extras = {{"angular_diameter", glm::degrees(double(l.angular_diameter))},
                {"intensity", double(l.intensity)}};
    }
    doc_["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
    nodes().push_back({{"name", "area_light"},
                       {"translation", vec(l.center)},
                       {"rotation", rotation(u, v, dir)},
                       {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
                       {"extras", {{"shadowbench_light", extras}}}});
  }

  std::vector<uint8_t> assemble() const {
    // Names may carry non-UTF-8 bytes from an imported file: replace, never throw.
    std::string text = doc_.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    while (text.size() % 4 != 0) text.push_back(' ');
    const size_t bin_size = (bin_.size() + 3) / 4 * 4;
    const size_t total = 12 + 8 + text.size() + (bin_size == 0 ? 0 : 8 + bin_size);
    if (total > 0xFFFFFFFFu) throw std::runtime_error("the scene is too big for a GLB (4 GiB)");
    std::vector<uint8_t> out(total, 0);
    size_t at = 0;
    const auto u32 = [&](size_t v) {
      for (int i = 0; i < 4; ++i) out[at++] = uint8_t((v >> (8 * i)) & 0xFF);
    };
    const auto bytes = [&](const void* data, size_t n) {
      if (n > 0) std::memcpy(out.data() + at, data, n);
      at += n;
    };
    bytes("glTF", 4);
    u32(2);
    u32(total);
    u32(text.size());
    u32(0x4E4F534Au);  // JSON
    bytes(text.data(), text.size());
    if (bin_size > 0) {
      u32(bin_size);
      u32(0x004E4942u);  // BIN, zero-padded (out starts zeroed)
      bytes(bin_.data(), bin_.size());
    }
    return out;
  }

  const Scene& scene_;
  json doc_ = json::object();
  std::vector<uint8_t> bin_;
  std::map<std::tuple<float, float, float, int, bool, float, bool>, int> materials_;
};

}  // namespace

std::vector<uint8_t> export_glb_bytes(const Scene& scene) { return GlbWriter(scene).write(); }

void export_glb(const Scene& scene, const std::string& path) {
  const std::vector<uint8_t> bytes = export_glb_bytes(scene);
  write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace sb
