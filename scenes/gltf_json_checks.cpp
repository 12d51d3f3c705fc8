#include "scenes/gltf_json_checks.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "scenes/gltf_accessors.h"
#include "scenes/gltf_import.h"

namespace sb::gltf {
namespace {

constexpr size_t kMaxJsonDepth = 64;

// nlohmann parses every non-negative integer literal as unsigned.
bool as_uint(const json& v, uint64_t& out) {
  if (!v.is_number_unsigned()) return false;
  out = v.get<uint64_t>();
  return true;
}

class JsonChecks : public ImportStep {
 public:
  JsonChecks(const std::string& file, const UriSandbox& sandbox)
      : ImportStep(file), sandbox_(sandbox) {}

  // JSON checks before tinygltf: what it would read or index unchecked, and
  // what it reports without saying where.
  void prevalidate(const unsigned char* data, size_t size) {
    json doc;
    try {
      doc = json::parse(data, data + size);
    } catch (const json::parse_error& e) {
      // "[json.exception.parse_error.101] parse error at line 3, column 9: syntax error ..."
      const std::string what = e.what();
      const size_t at = what.find("at line ");
      const size_t colon = at == std::string::npos ? at : what.find(": ", at);
      if (colon == std::string::npos) fail("JSON", what);
      fail("JSON " + what.substr(at + 3, colon - at - 3), what.substr(colon + 2));
    } catch (const json::out_of_range& e) {
      // A number too large for a double: "[json.exception.out_of_range.406]
      // number overflow parsing '1E400'" (found by tests/fuzz/fuzz_gltf).
      const std::string what = e.what();
      const size_t bracket = what.find("] ");
      fail("JSON", bracket == std::string::npos ? what : what.substr(bracket + 2));
    }
    if (!doc.is_object()) fail("JSON", "expected a glTF object, found " + describe(doc));
    check_depth(doc);

    const json* asset = doc.contains("asset") ? &doc["asset"] : nullptr;
    if (asset == nullptr || !asset->is_object()) fail("asset", "missing (required by glTF)");
    const json version = asset->value("version", json());
    if (!version.is_string() || version.get<std::string>().rfind("2.", 0) != 0)
      fail("asset",
           "version " +
               (version.is_string() ? quoted(version.get<std::string>()) : describe(version)) +
               " is not supported (only glTF 2.x)");

    if (doc.contains("extensionsRequired")) {
      const json& req = doc["extensionsRequired"];
      if (!req.is_array()) fail("extensionsRequired", "expected an array of names");
      static const char* supported[] = {"KHR_lights_punctual", "KHR_mesh_quantization",
                                        "KHR_texture_transform"};
      for (const auto& e : req) {
        bool ok = false;
        for (const char* s : supported) ok = ok || (e.is_string() && e.get<std::string>() == s);
        if (!ok)
          fail("extensionsRequired",
               "extension " + (e.is_string() ? quoted(e.get<std::string>()) : describe(e)) +
                   " is required by the file but not supported (supported: "
                   "KHR_lights_punctual, KHR_mesh_quantization, KHR_texture_transform)");
      }
    }

    std::vector<uint64_t> buffer_lengths;
    for_each(doc, "buffers", [&](const json& b, size_t i) {
      const std::string where = "buffer " + str(i);
      uint64_t length = 0;
      if (!b.contains("byteLength") || !as_uint(b["byteLength"], length) || length == 0)
        fail(where, "byteLength: expected a positive integer, found " +
                        (b.contains("byteLength") ? describe(b["byteLength"]) : "nothing"));
      buffer_lengths.push_back(length);
      if (b.contains("uri")) sandbox_.check_uri(b["uri"], where + " uri");
    });
    for_each(doc, "bufferViews", [&](const json& v, size_t i) {
      const std::string where = "bufferView " + str(i);
      uint64_t buffer = 0, offset = 0, length = 0;
      if (!v.contains("buffer") || !as_uint(v["buffer"], buffer))
        fail(where, "buffer: expected a buffer index, found " +
                        (v.contains("buffer") ? describe(v["buffer"]) : "nothing"));
      if (buffer >= buffer_lengths.size())
        fail(where, "buffer " + str(buffer) + " does not exist (" + str(buffer_lengths.size()) +
                        " buffers)");
      if (v.contains("byteOffset") && !as_uint(v["byteOffset"], offset))
        fail(where,
             "byteOffset: expected a non-negative integer, found " + describe(v["byteOffset"]));
      if (!v.contains("byteLength") || !as_uint(v["byteLength"], length) || length == 0)
        fail(where, "byteLength: expected a positive integer, found " +
                        (v.contains("byteLength") ? describe(v["byteLength"]) : "nothing"));
      const uint64_t total = buffer_lengths[buffer];
      if (length > total || offset > total - length)
        fail(where, "bytes [" + str(offset) + ", " + str(offset) + "+" + str(length) +
                        ") run past the end of buffer " + str(buffer) + " (byteLength " +
                        str(total) + ")");
    });
    for_each(doc, "accessors", [&](const json& a, size_t i) {
      const std::string where = "accessor " + str(i);
      uint64_t ctype = 0, count = 0;
      if (!a.contains("componentType") || !as_uint(a["componentType"], ctype) ||
          component_size(int(std::min<uint64_t>(ctype, 1u << 30))) == 0)
        fail(where, "componentType " +
                        (a.contains("componentType") ? a["componentType"].dump() : "missing") +
                        " is not one of 5120 (BYTE), 5121 (UNSIGNED_BYTE), 5122 (SHORT), "
                        "5123 (UNSIGNED_SHORT), 5125 (UNSIGNED_INT), 5126 (FLOAT)");
      const json type = a.value("type", json());
      static const char* types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
      bool type_ok = false;
      for (const char* t : types) type_ok = type_ok || (type.is_string() && type == t);
      if (!type_ok)
        fail(where, "type: expected SCALAR, VEC2..4 or MAT2..4, found " + describe(type));
      if (!a.contains("count") || !as_uint(a["count"], count) || count == 0)
        fail(where, "count: expected a positive integer, found " +
                        (a.contains("count") ? describe(a["count"]) : "nothing"));
      if (count > kGltfMaxElements)
        fail(where, "count " + str(count) + " exceeds the limit of " + str(kGltfMaxElements) +
                        " elements");
    });
    for_each(doc, "images", [&](const json& img, size_t i) {
      if (img.contains("uri")) sandbox_.check_uri(img["uri"], "image " + str(i) + " uri");
    });
    // tinygltf names neither the element nor the index for these.
    for (const char* key : {"nodes", "meshes", "materials", "textures", "samplers", "cameras",
                            "scenes", "skins", "animations"})
      for_each(doc, key, [](const json&, size_t) {});
    const size_t accessors = doc.value("accessors", json::array()).size();
    for_each(doc, "meshes", [&](const json& m, size_t i) {
      const std::string mesh = named(
          "mesh",
          m.value("name", json()).is_string() ? m["name"].get<std::string>() : std::string(), i);
      const json prims = m.value("primitives", json());
      if (!prims.is_array() || prims.empty())
        fail(mesh, "primitives: expected a non-empty array, found " + describe(prims));
      for (size_t k = 0; k < prims.size(); ++k) {
        const std::string where = mesh + " primitive " + str(k);
        const json& p = prims[k];
        if (!p.is_object()) fail(where, "expected an object, found " + describe(p));
        const json attributes = p.value("attributes", json());
        if (!attributes.is_object())
          fail(where, "attributes: expected an object, found " + describe(attributes));
        uint64_t a = 0;
        for (auto it = attributes.begin(); it != attributes.end(); ++it)
          if (!as_uint(it.value(), a) || a >= accessors)
            fail(where, it.key() + ": expected an accessor index below " + str(accessors) +
                            ", found " + describe(it.value()));
        if (p.contains("indices")) {
          if (!as_uint(p["indices"], a) || a >= accessors)
            fail(where, "indices: expected an accessor index below " + str(accessors) + ", found " +
                            describe(p["indices"]));
          if (!doc["accessors"][a].contains("bufferView"))
            fail(accessor_where(int(a), "indices of " + where), "indices need a bufferView");
        }
      }
    });
  }

  template <class F>
  void for_each(const json& doc, const char* key, F&& f) const {
    if (!doc.contains(key)) return;
    const json& arr = doc[key];
    if (!arr.is_array()) fail(key, "expected an array, found " + describe(arr));
    for (size_t i = 0; i < arr.size(); ++i) {
      if (!arr[i].is_object())
        fail(std::string(key) + "/" + str(i), "expected an object, found " + describe(arr[i]));
      f(arr[i], i);
    }
  }

  void check_depth(const json& doc) const {
    std::vector<std::pair<const json*, size_t>> stack{{&doc, 1}};
    while (!stack.empty()) {
      const auto [v, depth] = stack.back();
      stack.pop_back();
      if (depth > kMaxJsonDepth) fail("JSON", "nested more than " + str(kMaxJsonDepth) + " deep");
      if (v->is_structured())
        for (const auto& child : *v) stack.emplace_back(&child, depth + 1);
    }
  }

 private:
  const UriSandbox& sandbox_;
};

}  // namespace

void check_gltf_json(const std::string& file, const UriSandbox& sandbox, const unsigned char* data,
                     size_t size) {
  JsonChecks(file, sandbox).prevalidate(data, size);
}

}  // namespace sb::gltf
