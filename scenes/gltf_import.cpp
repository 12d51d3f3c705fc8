#include "scenes/gltf_import.h"

// Debian's libtinygltf is a compiled library: the header only declares it
// (TINYGLTF_IMPLEMENTATION must not be defined here).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/error.h"
#include "core/scene_types.h"

namespace sb {
namespace {

namespace fs = std::filesystem;
namespace tg = tinygltf;
using json = nlohmann::json;

constexpr size_t kMaxJsonDepth = 64;
// Accessors without a bufferView are zeros (plus sparse values): cap them so
// a tiny file cannot ask for gigabytes.
constexpr size_t kMaxUnbackedElements = 16u << 20;

std::string str(uint64_t v) { return std::to_string(v); }
std::string quoted(const std::string& s) {
  std::string q = s.size() > 80 ? s.substr(0, 77) + "..." : s;
  return "'" + q + "'";
}
// "node 'wheel' (5)" or "node 5".
std::string named(const std::string& kind, const std::string& name, size_t index) {
  return name.empty() ? kind + " " + str(index)
                      : kind + " " + quoted(name) + " (" + str(index) + ")";
}
std::string describe(const json& v) {
  std::string d = v.dump();
  if (d.size() > 40) d = d.substr(0, 37) + "...";
  return std::string(v.type_name()) + " " + d;
}
std::string first_line(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  return l.empty() ? "unknown error" : l;
}
// nlohmann parses every non-negative integer literal as unsigned.
bool as_uint(const json& v, uint64_t& out) {
  if (!v.is_number_unsigned()) return false;
  out = v.get<uint64_t>();
  return true;
}

// ---------------------------------------------------------------------------
// Files and URIs

// tinygltf decodes URIs this way (dlib::urldecode) before opening them, so the
// checks below look at exactly the name it will open.
std::string url_decode(const std::string& s) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size()) {
      // Invalid hex digits decode to garbage in tinygltf; refuse them instead.
      const int a = hex(s[i + 1]), b = hex(s[i + 2]);
      out += (a < 0 || b < 0) ? '\0' : static_cast<char>(a * 16 + b);
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool starts_with_ci(const std::string& s, const char* prefix) {
  const size_t n = std::strlen(prefix);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

// True when `p` (after resolving symbolic links) lies inside `dir` (canonical).
bool inside_folder(const fs::path& dir, const fs::path& p) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(p, ec);
  if (ec) return false;
  const fs::path rel = real.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// tinygltf reads buffers and images only through these, and only inside the
// glTF file's folder (it would also try the working directory, and expand
// '~' and environment variables, on its own).
struct Sandbox {
  fs::path dir;
};
bool sandbox_exists(const std::string& path, void* user) {
  std::error_code ec;
  return inside_folder(static_cast<Sandbox*>(user)->dir, path) && fs::is_regular_file(path, ec);
}
std::string sandbox_expand(const std::string& path, void*) { return path; }
bool sandbox_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                  void* user) {
  if (!sandbox_exists(path, user)) {
    if (err) *err = "outside the glTF file's folder or not a file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!in || ec || size > std::numeric_limits<uint32_t>::max()) {
    if (err) *err = "cannot read";
    return false;
  }
  out->resize(size);
  in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  if (!in) {
    if (err) *err = "cannot read";
    return false;
  }
  return true;
}
bool sandbox_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is disabled";
  return false;
}
// Keeps the encoded bytes; images are decoded later (and only if used) by
// OpenImageIO, which checks the size before it allocates.
bool keep_encoded_image(tg::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (size > 0) image->image.assign(bytes, bytes + size);
  image->width = image->height = image->component = image->bits = 0;
  return true;
}

std::vector<unsigned char> read_whole_file(const std::string& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(file, "", "file not found");
  if (!fs::is_regular_file(file, ec)) throw InputError(file, "", "not a regular file");
  const auto size = fs::file_size(file, ec);
  if (ec) throw InputError(file, "", "cannot read: " + ec.message());
  if (size > std::numeric_limits<uint32_t>::max())
    throw InputError(file, "", "larger than 4 GiB, the limit of glTF");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", std::string("cannot open: ") + std::strerror(errno));
  std::vector<unsigned char> bytes(size);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!in) throw InputError(file, "", "cannot read the whole file");
  if (bytes.empty()) throw InputError(file, "", "file is empty");
  return bytes;
}

uint32_t le32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

uint32_t be32(const unsigned char* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

uint32_t crc32(const unsigned char* p, size_t n) {
  static const auto table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

// "" when the PNG's chunks are complete and their CRCs match, else what is
// wrong. libpng reports such damage by longjmp through OpenImageIO, which
// leaks; checking first also gives a clearer message.
std::string png_damage(const std::vector<unsigned char>& b) {
  size_t at = 8;
  bool first = true;
  while (true) {
    if (b.size() - at < 12) return "truncated (no IEND chunk)";
    const uint32_t length = be32(&b[at]);
    if (length > b.size() - at - 12) return "truncated (chunk at byte " + str(at) + ")";
    const std::string type(reinterpret_cast<const char*>(&b[at + 4]), 4);
    if (crc32(&b[at + 4], 4 + size_t(length)) != be32(&b[at + 8 + length]))
      return "chunk " + quoted(type) + " at byte " + str(at) + " has a bad CRC (corrupt file)";
    if (first && (type != "IHDR" || length != 13)) return "does not start with an IHDR chunk";
    if (first) {
      const uint32_t w = be32(&b[at + 8]), h = be32(&b[at + 12]);
      if (w < 1 || h < 1 || w > uint32_t(kGltfMaxTextureSide) || h > uint32_t(kGltfMaxTextureSide))
        return "size " + str(w) + "x" + str(h) + " is outside [1, " +
               str(size_t(kGltfMaxTextureSide)) + "] per side";
    }
    if (type == "IEND") return "";
    first = false;
    at += 12 + size_t(length);
  }
}

// ---------------------------------------------------------------------------
// Accessor data

int component_size(int ctype) {
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "type " + std::to_string(type);
  }
}

// One component, normalised integers mapped to [0, 1] or [-1, 1] (glTF 3.11).
double read_component(const unsigned char* p, int ctype, bool normalized) {
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

uint32_t read_index(const unsigned char* p, int size) {
  if (size == 1) return p[0];
  if (size == 2) {
    uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// ---------------------------------------------------------------------------
// Extras (tinygltf::Value asserts on the wrong kind: check before every Get)

const tg::Value* member(const tg::Value& v, const char* key) {
  if (!v.IsObject() || !v.Has(key)) return nullptr;
  return &v.Get(key);
}
bool finite_number(const tg::Value* v, double& out) {
  if (v == nullptr || !v->IsNumber()) return false;
  out = v->GetNumberAsDouble();
  return std::isfinite(out);
}

struct LoadedPrimitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: flat normals are generated per instance
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;  // triangle list
  glm::vec3 albedo{1.0f};
  int texture = -1;
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

struct PendingCamera {
  bool found = false;
  glm::dvec3 eye, forward, up;
  double yfov = 0, znear = 0, zfar = 0, distance = 0;  // zfar 0: infinite
};

struct PendingLight {
  bool found = false;
  std::string type;
  glm::dvec3 position, direction, x_axis;
  double width = -1, height = -1, intensity = 1, distance = 0;
};

class Importer {
 public:
  Importer(std::string file, const GltfImportOptions& options)
      : file_(std::move(file)), options_(options) {}

  Scene run() {
    const std::vector<unsigned char> bytes = read_whole_file(file_);
    std::error_code ec;
    fs::path folder = fs::path(file_).parent_path();
    if (folder.empty()) folder = ".";
    sandbox_.dir = fs::weakly_canonical(fs::absolute(folder, ec), ec);
    if (ec) fail("", "cannot resolve the file's folder: " + ec.message());

    const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const unsigned char* json_begin = bytes.data();
    size_t json_size = bytes.size();
    if (glb) check_glb(bytes, json_begin, json_size);
    prevalidate(json_begin, json_size);
    parse_with_tinygltf(bytes, glb, json_begin, json_size);
    return build();
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file_, where, what);
  }

  // -------------------------------------------------------------------------
  // GLB container (tinygltf 2.7 trusts the BIN chunk's length a little).
  void check_glb(const std::vector<unsigned char>& b, const unsigned char*& json_begin,
                 size_t& json_size) const {
    const size_t n = b.size();
    if (n < 12)
      fail("GLB header", "file is truncated: " + str(n) + " bytes, the header alone needs 12");
    const uint32_t version = le32(&b[4]);
    if (version != 2) fail("GLB header", "version " + str(version) + " is not supported (only 2)");
    const uint32_t length = le32(&b[8]);
    if (length > n)
      fail("GLB header",
           "file is truncated: the header says " + str(length) + " bytes, the file has " + str(n));
    if (length < n)
      fail("GLB header", "the header says " + str(length) + " bytes but the file has " + str(n));
    if (n - 12 < 8) fail("GLB JSON chunk", "missing (the file is truncated)");
    const uint32_t json_length = le32(&b[12]);
    if (le32(&b[16]) != 0x4E4F534Au) fail("GLB JSON chunk", "the first chunk is not JSON");
    if (json_length == 0) fail("GLB JSON chunk", "empty");
    if (json_length > n - 20)
      fail("GLB JSON chunk",
           "its length " + str(json_length) + " runs past the end of the file (truncated?)");
    json_begin = &b[20];
    json_size = json_length;
    size_t offset = 20 + size_t(json_length);
    for (int chunk = 1; offset < n; ++chunk) {
      const std::string where = chunk == 1 ? "GLB BIN chunk" : "GLB chunk " + str(size_t(chunk));
      if (n - offset < 8) fail(where, "truncated chunk header at byte " + str(offset));
      const uint32_t length_i = le32(&b[offset]);
      const uint32_t type = le32(&b[offset + 4]);
      if (length_i > n - offset - 8)
        fail(where, "its length " + str(length_i) + " runs past the end of the file (truncated?)");
      if (type == 0x004E4942u && chunk != 1)
        fail(where, "a second BIN chunk (only one, right after the JSON chunk, is allowed)");
      offset += 8 + size_t(length_i);
    }
  }

  // -------------------------------------------------------------------------
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
      if (b.contains("uri")) check_uri(b["uri"], where + " uri");
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
      if (img.contains("uri")) check_uri(img["uri"], "image " + str(i) + " uri");
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

  void check_uri(const json& value, const std::string& where) const {
    if (!value.is_string()) fail(where, "expected a string, found " + describe(value));
    const std::string uri = value.get<std::string>();
    if (starts_with_ci(uri, "data:")) return;  // embedded, decoded by tinygltf
    const size_t end = uri.find_first_of(":/?#");
    if (end != std::string::npos && end > 0 && uri[end] == ':')
      fail(where, quoted(uri.substr(0, end + 1)) +
                      " URIs are not allowed (only data: URIs and relative paths inside the "
                      "glTF file's folder): " +
                      quoted(uri));
    const std::string path = url_decode(uri);
    if (path.empty()) fail(where, "empty");
    if (path.find('\0') != std::string::npos) fail(where, "invalid %-escape in " + quoted(uri));
    if (path[0] == '/' || path[0] == '\\')
      fail(where,
           "absolute paths are not allowed (only paths relative to the glTF file): " + quoted(uri));
    size_t start = 0;
    while (start <= path.size()) {
      const size_t stop = std::min(path.find_first_of("/\\", start), path.size());
      if (path.compare(start, stop - start, "..") == 0 && stop - start == 2)
        fail(where,
             "'..' segments are not allowed (files must be inside the glTF file's "
             "folder): " +
                 quoted(uri));
      start = stop + 1;
    }
    const fs::path full = sandbox_.dir / path;
    std::error_code ec;
    if (!fs::exists(full, ec))
      fail(where, "file " + quoted(path) + " not found next to the glTF file");
    if (!inside_folder(sandbox_.dir, full))
      fail(where, quoted(path) + " resolves outside the glTF file's folder (symbolic link)");
    if (!fs::is_regular_file(full, ec)) fail(where, quoted(path) + " is not a regular file");
  }

  // -------------------------------------------------------------------------
  void parse_with_tinygltf(const std::vector<unsigned char>& bytes, bool glb,
                           const unsigned char* json_begin, size_t json_size) {
    tg::TinyGLTF loader;
    loader.SetFsCallbacks(
        {&sandbox_exists, &sandbox_expand, &sandbox_read, &sandbox_write, &sandbox_});
    loader.SetImageLoader(&keep_encoded_image, nullptr);
    std::string err, warn;
    bool ok = false;
    const std::string base = sandbox_.dir.string();
    try {
      ok = glb ? loader.LoadBinaryFromMemory(&model_, &err, &warn, bytes.data(),
                                             static_cast<unsigned int>(bytes.size()), base)
               : loader.LoadASCIIFromString(&model_, &err, &warn,
                                            reinterpret_cast<const char*>(json_begin),
                                            static_cast<unsigned int>(json_size), base);
    } catch (const std::exception& e) {
      fail("", std::string("invalid glTF: ") + e.what());
    }
    if (!ok) fail("", "invalid glTF: " + first_line(err));
  }

  // -------------------------------------------------------------------------
  // Accessors

  struct Span {
    const unsigned char* data = nullptr;
    size_t stride = 0;
  };

  // Where `count` elements of `element` bytes start at `offset` in bufferView
  // `view`; throws unless all of them lie inside the view and its buffer.
  Span locate(int view, uint64_t offset, uint64_t count, uint64_t element, bool strided,
              const std::string& where) const {
    if (view < 0 || size_t(view) >= model_.bufferViews.size())
      fail(where, "bufferView " + std::to_string(view) + " does not exist (" +
                      str(model_.bufferViews.size()) + " bufferViews)");
    const tg::BufferView& v = model_.bufferViews[size_t(view)];
    const std::string vname = "bufferView " + str(size_t(view));
    if (v.buffer < 0 || size_t(v.buffer) >= model_.buffers.size())
      fail(where, vname + " names buffer " + std::to_string(v.buffer) + ", which does not exist");
    const auto& data = model_.buffers[size_t(v.buffer)].data;
    if (v.byteLength > data.size() || v.byteOffset > data.size() - v.byteLength)
      fail(where, vname + " runs past the end of buffer " + std::to_string(v.buffer));
    uint64_t stride = element;
    if (strided && v.byteStride != 0) {
      if (v.byteStride < element || v.byteStride > 252 || v.byteStride % 4 != 0)
        fail(where, vname + " has byteStride " + str(v.byteStride) +
                        ", expected a multiple of 4 in [" + str(element) + ", 252]");
      stride = v.byteStride;
    }
    if (offset > v.byteLength)
      fail(where, "byteOffset " + str(offset) + " is past the end of " + vname + " (byteLength " +
                      str(v.byteLength) + ")");
    // count <= kGltfMaxElements and stride <= 252: no overflow.
    const uint64_t need = (count - 1) * stride + element;
    if (need > v.byteLength - offset)
      fail(where, str(count) + " elements of " + str(element) + " bytes (stride " + str(stride) +
                      ") need " + str(need) + " bytes from byte " + str(offset) + " of " + vname +
                      ", which has only " + str(v.byteLength - offset));
    return {data.data() + v.byteOffset + offset, size_t(stride)};
  }

  const tg::Accessor& accessor(int index, const std::string& role) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(role, "accessor " + std::to_string(index) + " does not exist (" +
                     str(model_.accessors.size()) + " accessors)");
    return model_.accessors[size_t(index)];
  }

  std::string accessor_where(int index, const std::string& role) const {
    return "accessor " + std::to_string(index) + " (" + role + ")";
  }

  void check_count(const tg::Accessor& a, const std::string& where) const {
    if (a.count == 0 || a.count > kGltfMaxElements)
      fail(where, "count " + str(a.count) + " is outside [1, " + str(kGltfMaxElements) + "]");
    if (a.bufferView < 0 && a.count > kMaxUnbackedElements)
      fail(where, "count " + str(a.count) + " without a bufferView exceeds the limit of " +
                      str(kMaxUnbackedElements));
  }

  // Calls write(element index, bytes of one value) for each sparse entry.
  template <class F>
  void apply_sparse(const tg::Accessor& a, size_t element, const std::string& where,
                    F&& write) const {
    const auto& sp = a.sparse;
    if (sp.count < 1 || size_t(sp.count) > a.count)
      fail(where,
           "sparse.count " + std::to_string(sp.count) + " is outside [1, " + str(a.count) + "]");
    const int isize = sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                           : 0;
    if (isize == 0)
      fail(where, "sparse.indices.componentType " + std::to_string(sp.indices.componentType) +
                      " is not an unsigned integer type");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
      fail(where, "sparse byteOffset is negative");
    const uint64_t n = uint64_t(sp.count);
    const Span idx = locate(sp.indices.bufferView, uint64_t(sp.indices.byteOffset), n,
                            uint64_t(isize), false, where + " sparse.indices");
    const Span val = locate(sp.values.bufferView, uint64_t(sp.values.byteOffset), n, element, false,
                            where + " sparse.values");
    uint64_t previous = 0;
    for (size_t k = 0; k < n; ++k) {
      const uint32_t i = read_index(idx.data + k * idx.stride, isize);
      if (i >= a.count)
        fail(where, "sparse index " + str(i) + " is out of range (count " + str(a.count) + ")");
      if (k > 0 && i <= previous) fail(where, "sparse indices are not strictly increasing");
      previous = i;
      write(size_t(i), val.data + k * val.stride);
    }
  }

  // A VEC2/VEC3 attribute as floats, any component type (normalised or not).
  std::vector<float> read_floats(int index, int comps, const std::string& role) const {
    const tg::Accessor& a = accessor(index, role);
    const std::string where = accessor_where(index, role);
    const int expected = comps == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
    if (a.type != expected)
      fail(where, "expected type " + type_name(expected) + ", found " + type_name(a.type));
    const int csize = component_size(a.componentType);
    if (csize == 0) fail(where, "componentType " + std::to_string(a.componentType) + " is invalid");
    if (a.normalized && csize == 4)
      fail(where, "normalized is only allowed for 8- and 16-bit integer components");
    check_count(a, where);
    const size_t element = size_t(csize) * size_t(comps);
    // The bounds first: a 1 KB file may claim 3e8 elements.
    const Span s = a.bufferView >= 0
                       ? locate(a.bufferView, a.byteOffset, a.count, element, true, where)
                       : Span{nullptr, 0};
    std::vector<float> out(a.count * size_t(comps), 0.0f);
    const auto decode = [&](size_t i, const unsigned char* p) {
      for (int c = 0; c < comps; ++c)
        out[i * size_t(comps) + size_t(c)] =
            static_cast<float>(read_component(p + c * csize, a.componentType, a.normalized));
    };
    if (s.data != nullptr)
      for (size_t i = 0; i < a.count; ++i) decode(i, s.data + i * s.stride);
    if (a.sparse.isSparse) apply_sparse(a, element, where, decode);
    for (float v : out)
      if (!std::isfinite(v)) fail(where, "contains a non-finite value (NaN or infinity)");
    return out;
  }

  std::vector<uint32_t> read_indices(int index, const std::string& role, size_t vertices) const {
    const tg::Accessor& a = accessor(index, role);
    const std::string where = accessor_where(index, role);
    if (a.type != TINYGLTF_TYPE_SCALAR)
      fail(where, "expected type SCALAR for indices, found " + type_name(a.type));
    const int isize = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                  : 0;
    if (isize == 0 || a.normalized)
      fail(where,
           "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, found "
           "componentType " +
               std::to_string(a.componentType) + (a.normalized ? " (normalized)" : ""));
    check_count(a, where);
    const Span s = a.bufferView >= 0
                       ? locate(a.bufferView, a.byteOffset, a.count, uint64_t(isize), false, where)
                       : Span{nullptr, 0};
    std::vector<uint32_t> out(a.count, 0u);
    const auto decode = [&](size_t i, const unsigned char* p) { out[i] = read_index(p, isize); };
    if (s.data != nullptr)
      for (size_t i = 0; i < a.count; ++i) decode(i, s.data + i * s.stride);
    if (a.sparse.isSparse) apply_sparse(a, size_t(isize), where, decode);
    for (size_t i = 0; i < out.size(); ++i)
      if (out[i] >= vertices)
        fail(where, "index " + str(out[i]) + " (element " + str(i) +
                        ") is out of range: " + "POSITION has " + str(vertices) + " vertices");
    return out;
  }

  // -------------------------------------------------------------------------
  // Materials and textures

  int texture_for(int texture_index, const std::string& where) {
    if (texture_index < 0 || size_t(texture_index) >= model_.textures.size())
      fail(where, "baseColorTexture: texture " + std::to_string(texture_index) +
                      " does not exist (" + str(model_.textures.size()) + " textures)");
    const tg::Texture& t = model_.textures[size_t(texture_index)];
    const std::string twhere = named("texture", t.name, size_t(texture_index));
    if (t.source < 0)
      fail(twhere,
           "has no PNG or JPEG source image (EXT_texture_webp and KHR_texture_basisu "
           "are not supported)");
    if (size_t(t.source) >= model_.images.size())
      fail(twhere, "source image " + std::to_string(t.source) + " does not exist (" +
                       str(model_.images.size()) + " images)");
    // Images shared by textures and materials become one Scene texture.
    const auto found = image_to_texture_.find(t.source);
    if (found != image_to_texture_.end()) return found->second;
    scene_.textures.push_back(decode_image(size_t(t.source)));
    const int sb_index = int(scene_.textures.size() - 1);
    image_to_texture_[t.source] = sb_index;
    return sb_index;
  }

  TextureImage decode_image(size_t index) {
    const tg::Image& img = model_.images[index];
    const std::string where = named("image", img.name, index);
    const std::vector<unsigned char>& bytes = img.image;
    if (bytes.empty())
      fail(img.uri.empty() ? where : where + " uri", "no image data could be read");
    static const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    std::string ext;
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), png, 8) == 0)
      ext = "png";
    else if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
      ext = "jpg";
    else
      fail(where, "is neither a PNG nor a JPEG image (mimeType " + quoted(img.mimeType) + ")");
    if (ext == "png")
      if (const std::string damage = png_damage(bytes); !damage.empty())
        fail(where, "PNG " + damage);
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // glTF alpha is straight: keep rgb as stored
    // With a config, readers take the proxy from it (OIIO 2.4), not from open()'s argument.
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open("image." + ext, &config, &memory);
    if (!in) fail(where, "cannot decode the " + ext + " image: " + first_line(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.width > kGltfMaxTextureSide ||
        spec.height > kGltfMaxTextureSide || spec.depth != 1)
      fail(where, "size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                      " is outside [1, " + std::to_string(kGltfMaxTextureSide) + "] per side");
    const int channels = spec.nchannels;
    if (channels < 1 || channels > 4)
      fail(where, std::to_string(channels) + " channels (expected 1 to 4)");
    const size_t texels = size_t(spec.width) * size_t(spec.height);
    // Checked on the header, before decoding: small files can unpack to gigabytes.
    decoded_texels_ += texels;
    if (decoded_texels_ > kGltfMaxDecodedTexels)
      fail(where, "decoding it would bring the scene's textures to " + str(decoded_texels_) +
                      " texels, over the limit of " + str(kGltfMaxDecodedTexels));
    std::vector<uint8_t> raw(texels * size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data()))
      fail(where, "cannot decode the " + ext + " image: " + first_line(in->geterror()));
    TextureImage t;
    t.name = img.name.empty() ? "image" + str(index) : img.name;
    t.width = spec.width;
    t.height = spec.height;
    t.rgba.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i) {
      const uint8_t* s = &raw[i * size_t(channels)];
      uint8_t* d = &t.rgba[i * 4];
      const bool grey = channels <= 2;
      d[0] = s[0];
      d[1] = grey ? s[0] : s[1];
      d[2] = grey ? s[0] : s[2];
      d[3] = channels == 2 ? s[1] : channels == 4 ? s[3] : 255;
    }
    return t;
  }

  struct MaterialInfo {
    glm::vec3 albedo{1.0f};
    int texture = -1;
    int texcoord = 0;
    AlphaMode mode = AlphaMode::Opaque;
    float cutoff = 0.5f;
    bool double_sided = false;
    bool transform = false;
    glm::dmat3 uv_transform{1.0};  // column-major: uv' = M * (u, v, 1)
  };

  MaterialInfo material(int index, const std::string& primitive) {
    MaterialInfo info;  // glTF's default material: white, opaque
    if (index < 0) return info;
    if (size_t(index) >= model_.materials.size())
      fail(primitive, "material " + std::to_string(index) + " does not exist (" +
                          str(model_.materials.size()) + " materials)");
    const tg::Material& m = model_.materials[size_t(index)];
    const std::string where = named("material", m.name, size_t(index));
    const auto& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4) fail(where, "baseColorFactor: expected 4 numbers");
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(f[size_t(c)])) fail(where, "baseColorFactor is not finite");
      info.albedo[c] = static_cast<float>(std::clamp(f[size_t(c)], 0.0, 1.0));
    }
    if (m.alphaMode == "MASK") {
      if (!std::isfinite(m.alphaCutoff) || m.alphaCutoff < 0)
        fail(where, "alphaCutoff must be a non-negative number");
      info.mode = AlphaMode::Mask;
      info.cutoff = static_cast<float>(m.alphaCutoff);
    } else if (m.alphaMode == "BLEND") {
      info.mode = AlphaMode::Mask;  // no blending in the benchmark: coverage at 0.5
      info.cutoff = 0.5f;
    } else if (m.alphaMode != "OPAQUE") {
      fail(where, "alphaMode " + quoted(m.alphaMode) + " is not OPAQUE, MASK or BLEND");
    }
    info.double_sided = m.doubleSided;
    const tg::TextureInfo& tex = m.pbrMetallicRoughness.baseColorTexture;
    if (tex.index >= 0) {
      info.texture = texture_for(tex.index, where);
      info.texcoord = tex.texCoord;
      const auto ext = tex.extensions.find("KHR_texture_transform");
      if (ext != tex.extensions.end()) texture_transform(ext->second, where, info);
    }
    if (info.texcoord < 0 || info.texcoord > 7)
      fail(where, "baseColorTexture.texCoord " + std::to_string(info.texcoord) + " is invalid");
    return info;
  }

  // KHR_texture_transform is baked into the UVs (one material per Mesh here).
  void texture_transform(const tg::Value& t, const std::string& where, MaterialInfo& info) const {
    const std::string w = where + " KHR_texture_transform";
    const auto pair = [&](const char* key, glm::dvec2 def) {
      const tg::Value* v = member(t, key);
      if (v == nullptr) return def;
      double a = 0, b = 0;
      if (!v->IsArray() || v->ArrayLen() != 2 || !finite_number(&v->Get(0), a) ||
          !finite_number(&v->Get(1), b))
        fail(w, std::string(key) + ": expected 2 numbers");
      return glm::dvec2(a, b);
    };
    const glm::dvec2 offset = pair("offset", glm::dvec2(0.0));
    const glm::dvec2 scale = pair("scale", glm::dvec2(1.0));
    double rotation = 0;
    if (member(t, "rotation") != nullptr && !finite_number(member(t, "rotation"), rotation))
      fail(w, "rotation: expected a number");
    if (const tg::Value* tc = member(t, "texCoord")) {
      if (!tc->IsInt()) fail(w, "texCoord: expected an integer");
      info.texcoord = tc->Get<int>();
    }
    const double c = std::cos(rotation), s = std::sin(rotation);
    // T * R * S from the extension's spec, written column by column.
    info.uv_transform =
        glm::dmat3(glm::dvec3(c * scale.x, -s * scale.x, 0),
                   glm::dvec3(s * scale.y, c * scale.y, 0), glm::dvec3(offset.x, offset.y, 1));
    info.transform = true;
  }

  // -------------------------------------------------------------------------
  // Primitives (loaded once per glTF mesh, instanced per node)

  LoadedPrimitive load_primitive(size_t mesh_index, size_t prim_index) {
    const tg::Mesh& mesh = model_.meshes[mesh_index];
    const tg::Primitive& p = mesh.primitives[prim_index];
    const std::string where =
        named("mesh", mesh.name, mesh_index) + " primitive " + str(prim_index);
    const int mode = p.mode;
    if (mode < 0 || mode > 6)
      fail(where, "mode " + std::to_string(mode) + " is not a primitive mode");
    static const char* lower_modes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
    if (mode >= 0 && mode <= 3)
      fail(where, "mode " + std::string(lower_modes[mode]) + " (" + std::to_string(mode) +
                      ") is not supported: only triangles, triangle strips and fans are");

    const auto attribute = [&](const std::string& name) {
      const auto it = p.attributes.find(name);
      return it == p.attributes.end() ? -1 : it->second;
    };
    const int position = attribute("POSITION");
    if (position < 0) fail(where, "has no POSITION attribute");

    // Count the triangles before reading anything big.
    const tg::Accessor& pa = accessor(position, "POSITION of " + where);
    check_count(pa, accessor_where(position, "POSITION of " + where));
    size_t elements = pa.count;
    if (p.indices >= 0) {
      const tg::Accessor& ia = accessor(p.indices, "indices of " + where);
      check_count(ia, accessor_where(p.indices, "indices of " + where));
      elements = ia.count;
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && elements % 3 != 0)
      fail(where, "TRIANGLES with " + str(elements) + " vertices or indices, not a multiple of 3");
    const size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? elements / 3
                             : elements >= 3                 ? elements - 2
                                                             : 0;
    if (triangles > kGltfMaxTriangles)
      fail(where, str(triangles) + " triangles exceed the limit of " + str(kGltfMaxTriangles));

    LoadedPrimitive out;
    const MaterialInfo mat = material(p.material, where);
    out.albedo = mat.albedo;
    out.texture = mat.texture;
    out.alpha_mode = mat.mode;
    out.alpha_cutoff = mat.cutoff;
    out.double_sided = mat.double_sided;

    const std::vector<float> pos = read_floats(position, 3, "POSITION of " + where);
    const size_t n = pos.size() / 3;
    out.positions.resize(n);
    std::memcpy(out.positions.data(), pos.data(), pos.size() * sizeof(float));

    if (const int normal = attribute("NORMAL"); normal >= 0) {
      const std::vector<float> nor = read_floats(normal, 3, "NORMAL of " + where);
      if (nor.size() != pos.size())
        fail(where, "NORMAL has " + str(nor.size() / 3) + " elements but POSITION has " + str(n));
      out.normals.resize(n);
      std::memcpy(out.normals.data(), nor.data(), nor.size() * sizeof(float));
    }

    const std::string uv_name = "TEXCOORD_" + std::to_string(mat.texcoord);
    const int uv = attribute(uv_name);
    if (mat.texture >= 0 && uv < 0)
      fail(where, "its material's baseColorTexture uses " + uv_name + ", which it does not have");
    if (uv >= 0) {
      const std::vector<float> tc = read_floats(uv, 2, uv_name + " of " + where);
      if (tc.size() / 2 != n)
        fail(where,
             uv_name + " has " + str(tc.size() / 2) + " elements but POSITION has " + str(n));
      out.uvs.resize(n);
      for (size_t i = 0; i < n; ++i) {
        glm::dvec3 t(tc[2 * i], tc[2 * i + 1], 1.0);
        if (mat.transform) t = mat.uv_transform * t;
        out.uvs[i] = glm::vec2(float(t.x), float(t.y));
      }
    }

    std::vector<uint32_t> idx;
    if (p.indices >= 0) {
      idx = read_indices(p.indices, "indices of " + where, n);
    } else {
      idx.resize(n);
      for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
    }
    out.indices.reserve(triangles * 3);
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      out.indices = std::move(idx);
    } else {
      for (size_t i = 0; i < triangles; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
          out.indices.insert(out.indices.end(), {idx[0], idx[i + 1], idx[i + 2]});
        else if (i % 2 == 0)  // strips alternate winding
          out.indices.insert(out.indices.end(), {idx[i], idx[i + 1], idx[i + 2]});
        else
          out.indices.insert(out.indices.end(), {idx[i + 1], idx[i], idx[i + 2]});
      }
    }
    return out;
  }

  const std::vector<LoadedPrimitive>& mesh_primitives(size_t mesh_index) {
    auto it = loaded_.find(mesh_index);
    if (it != loaded_.end()) return it->second;
    std::vector<LoadedPrimitive> prims;
    const tg::Mesh& mesh = model_.meshes[mesh_index];
    for (size_t i = 0; i < mesh.primitives.size(); ++i)
      prims.push_back(load_primitive(mesh_index, i));
    return loaded_.emplace(mesh_index, std::move(prims)).first->second;
  }

  static bool casts_shadow_flag(const tg::Value& extras, bool def) {
    const tg::Value* sb = member(extras, "shadowbench_mesh");
    const tg::Value* flag = sb ? member(*sb, "casts_shadow") : nullptr;
    return flag != nullptr && flag->IsBool() ? flag->Get<bool>() : def;
  }

  void instantiate(size_t node_index, const glm::dmat4& world) {
    const tg::Node& node = model_.nodes[node_index];
    const std::string where = named("node", node.name, node_index);
    if (size_t(node.mesh) >= model_.meshes.size())
      fail(where, "mesh " + std::to_string(node.mesh) + " does not exist (" +
                      str(model_.meshes.size()) + " meshes)");
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    if (det == 0.0) return;  // zero scale: nothing visible (documented)
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    const bool mirrored = det < 0.0;

    const tg::Mesh& gmesh = model_.meshes[size_t(node.mesh)];
    const std::vector<LoadedPrimitive>& prims = mesh_primitives(size_t(node.mesh));
    const bool casts = casts_shadow_flag(node.extras, casts_shadow_flag(gmesh.extras, true));
    for (size_t pi = 0; pi < prims.size(); ++pi) {
      const LoadedPrimitive& p = prims[pi];
      const size_t triangles = p.indices.size() / 3;
      if (triangles == 0) continue;
      if (triangles > kGltfMaxTriangles - total_triangles_)
        fail(where, "the scene exceeds the limit of " + str(kGltfMaxTriangles) +
                        " triangles (after instancing)");
      total_triangles_ += triangles;

      Mesh m;
      m.name = !node.name.empty()    ? node.name
               : !gmesh.name.empty() ? gmesh.name
                                     : "mesh" + std::to_string(node.mesh);
      if (prims.size() > 1) m.name += "/" + str(pi);
      m.albedo = p.albedo;
      m.base_color_texture = p.texture;
      m.alpha_mode = p.alpha_mode;
      m.alpha_cutoff = p.alpha_cutoff;
      m.double_sided = p.double_sided;
      m.casts_shadow = casts;

      std::vector<glm::vec3> positions(p.positions.size());
      for (size_t i = 0; i < positions.size(); ++i) {
        const glm::dvec3 q = glm::dvec3(world * glm::dvec4(glm::dvec3(p.positions[i]), 1.0));
        positions[i] = glm::vec3(q);
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) ||
            !std::isfinite(positions[i].z))
          fail(where, "its transform takes a vertex of mesh " + std::to_string(node.mesh) +
                          " to infinity");
      }
      std::vector<uint32_t> indices = p.indices;
      if (mirrored)  // a mirroring transform turns counter-clockwise into clockwise
        for (size_t t = 0; t < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);

      if (!p.normals.empty()) {
        m.positions = std::move(positions);
        m.indices = std::move(indices);
        m.uvs = p.uvs;
        m.normals.resize(p.normals.size());
        for (size_t i = 0; i < p.normals.size(); ++i) {
          const glm::dvec3 nv = normal_matrix * glm::dvec3(p.normals[i]);
          const double len = glm::length(nv);
          m.normals[i] = len > 0 ? glm::vec3(nv / len) : glm::vec3(0.0f);
        }
      } else {
        // glTF: without normals, flat shading (one vertex per corner).
        m.positions.reserve(indices.size());
        m.normals.reserve(indices.size());
        if (!p.uvs.empty()) m.uvs.reserve(indices.size());
        for (size_t t = 0; t < indices.size(); t += 3) {
          const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]],
                          c = positions[indices[t + 2]];
          const glm::vec3 cr = glm::cross(b - a, c - a);
          const float len = glm::length(cr);
          const glm::vec3 n = len > 0 ? cr / len : glm::vec3(0.0f, 1.0f, 0.0f);
          for (int k = 0; k < 3; ++k) {
            m.positions.push_back(positions[indices[t + size_t(k)]]);
            m.normals.push_back(n);
            if (!p.uvs.empty()) m.uvs.push_back(p.uvs[indices[t + size_t(k)]]);
            m.indices.push_back(uint32_t(t + size_t(k)));
          }
        }
      }
      scene_.meshes.push_back(std::move(m));
    }
  }

  // -------------------------------------------------------------------------
  // Node hierarchy

  glm::dmat4 local_matrix(const tg::Node& n, const std::string& where) const {
    const auto finite = [&](const std::vector<double>& v, const char* what) {
      for (double x : v)
        if (!std::isfinite(x)) fail(where, std::string(what) + " is not finite");
    };
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16)
        fail(where, "matrix has " + str(n.matrix.size()) + " numbers, expected 16");
      if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
        fail(where, "has both a matrix and translation/rotation/scale");
      finite(n.matrix, "matrix");
      glm::dmat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c) * 4 + size_t(r)];
      return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) fail(where, "translation: expected 3 numbers");
      finite(n.translation, "translation");
      t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) fail(where, "rotation: expected 4 numbers (x, y, z, w)");
      finite(n.rotation, "rotation");
      glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      const double len = glm::length(q);
      if (!(len > 1e-6)) fail(where, "rotation is not a unit quaternion");
      r = glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) fail(where, "scale: expected 3 numbers");
      finite(n.scale, "scale");
      s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return t * r * s;
  }

  // Children must form a forest: one parent each, no cycles.
  std::vector<int> check_hierarchy() const {
    const size_t n = model_.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
      const tg::Node& node = model_.nodes[i];
      for (int c : node.children) {
        const std::string where = named("node", node.name, i);
        if (c < 0 || size_t(c) >= n)
          fail(where, "child " + std::to_string(c) + " does not exist (" + str(n) + " nodes)");
        if (size_t(c) == i) fail(where, "is its own child");
        if (parent[size_t(c)] >= 0)
          fail(named("node", model_.nodes[size_t(c)].name, size_t(c)),
               "has two parents, nodes " + std::to_string(parent[size_t(c)]) + " and " + str(i) +
                   " (the node hierarchy must be a tree)");
        parent[size_t(c)] = int(i);
      }
    }
    std::vector<char> state(n, 0);  // 0 unseen, 1 on the current walk, 2 known to end at a root
    for (size_t i = 0; i < n; ++i) {
      std::vector<size_t> walk;
      int x = int(i);
      while (x >= 0 && state[size_t(x)] == 0) {
        state[size_t(x)] = 1;
        walk.push_back(size_t(x));
        x = parent[size_t(x)];
      }
      if (x >= 0 && state[size_t(x)] == 1)
        fail(named("node", model_.nodes[size_t(x)].name, size_t(x)),
             "is its own ancestor: the node hierarchy has a cycle");
      for (size_t w : walk) state[w] = 2;
    }
    return parent;
  }

  void visit_camera(size_t node_index, const glm::dmat4& world) {
    const tg::Node& node = model_.nodes[node_index];
    const std::string nwhere = named("node", node.name, node_index);
    if (size_t(node.camera) >= model_.cameras.size())
      fail(nwhere, "camera " + std::to_string(node.camera) + " does not exist (" +
                       str(model_.cameras.size()) + " cameras)");
    const tg::Camera& cam = model_.cameras[size_t(node.camera)];
    if (cam.type != "perspective") return;  // orthographic cameras are skipped (documented)
    const std::string where = named("camera", cam.name, size_t(node.camera));
    const auto& p = cam.perspective;
    if (!std::isfinite(p.yfov) || p.yfov <= 0 || p.yfov >= std::numbers::pi)
      fail(where, "yfov " + json(p.yfov).dump() + " is outside (0, pi) radians");
    if (!std::isfinite(p.znear) || p.znear <= 0)
      fail(where, "znear " + json(p.znear).dump() + " must be positive");
    if (!std::isfinite(p.zfar) || (p.zfar != 0 && p.zfar <= p.znear))
      fail(where, "zfar " + json(p.zfar).dump() + " must be greater than znear");
    camera_.eye = glm::dvec3(world[3]);
    camera_.forward = glm::dvec3(world * glm::dvec4(0, 0, -1, 0));
    camera_.up = glm::dvec3(world * glm::dvec4(0, 1, 0, 0));
    if (!(glm::length(camera_.forward) > 0) || !(glm::length(camera_.up) > 0) ||
        glm::length(glm::cross(camera_.forward, camera_.up)) == 0)
      fail(nwhere, "the camera's transform is degenerate");
    camera_.forward = glm::normalize(camera_.forward);
    camera_.up = glm::normalize(camera_.up);
    camera_.yfov = p.yfov;
    camera_.znear = p.znear;
    camera_.zfar = p.zfar;
    const tg::Value* sb = member(node.extras, "shadowbench_camera");
    double d = 0;
    if (sb != nullptr && finite_number(member(*sb, "target_distance"), d) && d > 0)
      camera_.distance = d;
    camera_.found = true;
  }

  bool visit_light(size_t node_index, const glm::dmat4& world) {
    const tg::Node& node = model_.nodes[node_index];
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return false;
    const std::string nwhere = named("node", node.name, node_index);
    const tg::Value* li = member(ext->second, "light");
    if (li == nullptr || !li->IsInt())
      fail(nwhere, "KHR_lights_punctual: expected {\"light\": index}");
    const int index = li->Get<int>();
    if (index < 0 || size_t(index) >= model_.lights.size())
      fail(nwhere, "KHR_lights_punctual light " + std::to_string(index) + " does not exist (" +
                       str(model_.lights.size()) + " lights)");
    const tg::Light& l = model_.lights[size_t(index)];
    if (l.type != "spot" && l.type != "point" && l.type != "directional")
      fail(named("light", l.name, size_t(index)),
           "type " + quoted(l.type) + " is not spot, point or directional");
    light_.type = l.type;
    light_.position = glm::dvec3(world[3]);
    light_.direction = glm::dvec3(world * glm::dvec4(0, 0, -1, 0));
    light_.x_axis = glm::dvec3(world * glm::dvec4(1, 0, 0, 0));
    if (!(glm::length(light_.direction) > 0) || !(glm::length(light_.x_axis) > 0))
      fail(nwhere, "the light's transform is degenerate");
    light_.direction = glm::normalize(light_.direction);
    if (const tg::Value* sb = member(node.extras, "shadowbench_light")) {
      const std::string w = nwhere + " extras.shadowbench_light";
      if (const tg::Value* size = member(*sb, "size")) {
        if (!size->IsArray() || size->ArrayLen() != 2 ||
            !finite_number(&size->Get(0), light_.width) ||
            !finite_number(&size->Get(1), light_.height) || light_.width < 0 || light_.height < 0)
          fail(w, "size: expected [width, height], two non-negative numbers");
      }
      if (member(*sb, "intensity") != nullptr &&
          (!finite_number(member(*sb, "intensity"), light_.intensity) || light_.intensity < 0))
        fail(w, "intensity: expected a non-negative number");
      double d = 0;
      if (finite_number(member(*sb, "target_distance"), d) && d > 0) light_.distance = d;
    }
    light_.found = true;
    return true;
  }

  void traverse() {
    const std::vector<int> parent = check_hierarchy();
    std::vector<size_t> roots;
    if (!model_.scenes.empty()) {
      int si = model_.defaultScene < 0 ? 0 : model_.defaultScene;
      if (size_t(si) >= model_.scenes.size())
        fail("scene", "the default scene " + std::to_string(si) + " does not exist (" +
                          str(model_.scenes.size()) + " scenes)");
      const tg::Scene& s = model_.scenes[size_t(si)];
      for (int r : s.nodes) {
        if (r < 0 || size_t(r) >= model_.nodes.size())
          fail(named("scene", s.name, size_t(si)), "node " + std::to_string(r) +
                                                       " does not exist (" +
                                                       str(model_.nodes.size()) + " nodes)");
        if (parent[size_t(r)] >= 0)
          fail(named("node", model_.nodes[size_t(r)].name, size_t(r)),
               "is a root of the scene but also the child of node " +
                   std::to_string(parent[size_t(r)]));
        roots.push_back(size_t(r));
      }
      if (const tg::Value* sb = member(s.extras, "shadowbench_scene")) {
        const tg::Value* a = member(*sb, "ambient");
        double c[3];
        if (a != nullptr && a->IsArray() && a->ArrayLen() == 3 && finite_number(&a->Get(0), c[0]) &&
            finite_number(&a->Get(1), c[1]) && finite_number(&a->Get(2), c[2]))
          scene_.ambient = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
      }
    } else {  // no scenes: every root node
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (parent[i] < 0) roots.push_back(i);
    }
    // Depth-first, in file order, without recursion (hierarchies can be deep).
    std::vector<std::pair<size_t, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.emplace_back(*it, glm::dmat4(1.0));
    while (!stack.empty()) {
      const auto [index, parent_world] = stack.back();
      stack.pop_back();
      const tg::Node& node = model_.nodes[index];
      const std::string where = named("node", node.name, index);
      const glm::dmat4 world = parent_world * local_matrix(node, where);
      if (node.mesh != -1) instantiate(index, world);
      if (node.camera != -1 && !camera_.found) visit_camera(index, world);
      if (!light_.found) visit_light(index, world);
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
        stack.emplace_back(size_t(*c), world);
    }
  }

  // -------------------------------------------------------------------------
  Scene build() {
    scene_.name = fs::path(file_).stem().string();
    traverse();
    if (scene_.triangle_count() == 0) fail("scene", "the default scene has no triangles");

    const Bounds b = scene_.bounds();
    const glm::dvec3 center(b.center());
    const double radius = std::max(double(b.radius()), 1e-3);

    Camera& cam = scene_.camera;
    if (camera_.found) {
      cam.eye = glm::vec3(camera_.eye);
      const double d = camera_.distance > 0 ? camera_.distance
                                            : std::max(glm::length(center - camera_.eye), 1e-3);
      cam.target = glm::vec3(camera_.eye + camera_.forward * d);
      cam.up = glm::vec3(camera_.up);
      cam.fov_y_degrees = float(glm::degrees(camera_.yfov));
      cam.near_plane = float(camera_.znear);
      double far = camera_.zfar;
      if (far == 0) {  // infinite: far enough for the whole scene
        far = 0;
        for (int k = 0; k < 8; ++k) {
          const glm::dvec3 corner(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y,
                                  k & 4 ? b.hi.z : b.lo.z);
          far = std::max(far, glm::length(corner - camera_.eye));
        }
        far = std::max(far * 1.1, camera_.znear * 2);
      }
      cam.far_plane = float(far);
    } else {  // frame the bounds from the front, a little above
      cam.fov_y_degrees = 45.0f;
      const double dist = radius / std::sin(glm::radians(22.5)) * 1.1;
      const glm::dvec3 eye = center + glm::normalize(glm::dvec3(0, 0.5, 1)) * dist;
      cam.eye = glm::vec3(eye);
      cam.target = glm::vec3(center);
      cam.up = glm::vec3(0, 1, 0);
      cam.near_plane = float(std::max((dist - radius) * 0.5, dist * 1e-3));
      cam.far_plane = float(dist + 2 * radius);
    }

    const double default_size = 0.05 * 2 * radius;
    AreaLight& light = scene_.light;
    glm::dvec3 lc, lt;
    double w = light_.width >= 0 ? light_.width : default_size;
    double h = light_.height >= 0 ? light_.height : default_size;
    const float intensity = float(light_.intensity);
    bool use_axes = false;
    if (light_.found && light_.type == "spot") {
      lc = light_.position;
      const double d =
          light_.distance > 0 ? light_.distance : std::max(glm::length(center - lc), 1e-3 * radius);
      lt = lc + light_.direction * d;
      use_axes = true;
    } else if (light_.found && light_.type == "point") {
      lc = light_.position;
      lt = glm::length(center - lc) > 0 ? center : lc - glm::dvec3(0, 1, 0);
    } else if (light_.found) {  // directional: from outside the bounds, along its direction
      lt = center;
      lc = center - light_.direction * (3 * radius);
    } else {  // above the scene, like sphere_grid's light
      lt = center;
      lc = center + glm::normalize(glm::dvec3(0.35, 1, 0.25)) * (3 * radius);
    }
    light = make_area_light(glm::vec3(lc), glm::vec3(lt), float(w), float(h), intensity);
    if (use_axes) {
      // The node's x axis spans the rectangle's width (export writes it so).
      const glm::dvec3 dir = glm::normalize(lt - lc);
      glm::dvec3 u = light_.x_axis - dir * glm::dot(light_.x_axis, dir);
      if (glm::length(u) > 1e-9) {
        u = glm::normalize(u);
        const glm::dvec3 v = glm::normalize(glm::cross(u, dir));
        light.half_u = glm::vec3(u * (0.5 * w));
        light.half_v = glm::vec3(v * (0.5 * h));
      }
    }

    apply_scale();
    return std::move(scene_);
  }

  void apply_scale() {
    const float s = options_.scale;
    if (s != 1.0f) {
      for (auto& m : scene_.meshes)
        for (auto& p : m.positions) p *= s;
      AreaLight& l = scene_.light;
      l.center *= s;
      l.target *= s;
      l.half_u *= s;
      l.half_v *= s;
      Camera& c = scene_.camera;
      c.eye *= s;
      c.target *= s;
      c.near_plane *= s;
      c.far_plane *= s;
    }
    if (options_.light_size > 0) {
      AreaLight& l = scene_.light;
      const float size = options_.light_size;
      if (glm::length(l.half_u) > 0 && glm::length(l.half_v) > 0) {
        l.half_u = glm::normalize(l.half_u) * (0.5f * size);
        l.half_v = glm::normalize(l.half_v) * (0.5f * size);
      } else {
        l = make_area_light(l.center, l.target, size, size, l.intensity);
      }
    }
  }

  std::string file_;
  GltfImportOptions options_;
  Sandbox sandbox_;
  tg::Model model_;
  Scene scene_;
  std::map<size_t, std::vector<LoadedPrimitive>> loaded_;
  std::map<int, int> image_to_texture_;
  size_t decoded_texels_ = 0;  // of every image decoded so far
  size_t total_triangles_ = 0;
  PendingCamera camera_;
  PendingLight light_;
};

}  // namespace

Scene load_gltf(const std::string& path, const GltfImportOptions& options) {
  return Importer(path, options).run();
}

}  // namespace sb
