#pragma once
// Small glTF writer for tests: accessors over one binary buffer, saved as
// .gltf (+ external .bin or a data: URI) or .glb.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace sb::test {

using json = nlohmann::json;

inline std::string base64(const std::vector<uint8_t>& in) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t v = uint32_t(in[i]) << 16;
    if (i + 1 < in.size()) v |= uint32_t(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= in[i + 2];
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < in.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? table[v & 63] : '=';
  }
  return out;
}

inline void write_bytes(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

inline std::vector<uint8_t> read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// A fresh folder under the system temp dir, removed at destruction.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "sb_gltf_XXXXXX").string();
    path = mkdtemp(t.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

struct GltfBuilder {
  json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  json& arr(const char* key) {
    if (!doc.contains(key)) doc[key] = json::array();
    return doc[key];
  }
  int view(const void* data, size_t bytes, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    bin.insert(bin.end(), static_cast<const uint8_t*>(data),
               static_cast<const uint8_t*>(data) + bytes);
    arr("bufferViews").push_back(v);
    return int(arr("bufferViews").size() - 1);
  }
  template <class T>
  int accessor(const std::vector<T>& values, int ctype, const char* type, size_t count,
               bool normalized = false) {
    json a = {{"bufferView", view(values.data(), values.size() * sizeof(T))},
              {"componentType", ctype},
              {"count", count},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    arr("accessors").push_back(a);
    return int(arr("accessors").size() - 1);
  }
  int positions(const std::vector<float>& xyz) {
    return accessor(xyz, 5126, "VEC3", xyz.size() / 3);
  }
  // A mesh with one primitive, and a root node instancing it.
  int mesh(const json& primitive, const std::string& name = "") {
    json m = {{"primitives", json::array({primitive})}};
    if (!name.empty()) m["name"] = name;
    arr("meshes").push_back(m);
    return int(arr("meshes").size() - 1);
  }
  int node(json n, bool root = true) {
    arr("nodes").push_back(std::move(n));
    const int index = int(arr("nodes").size() - 1);
    if (root) {
      if (!doc.contains("scenes")) doc["scenes"] = json::array({{{"nodes", json::array()}}});
      doc["scenes"][0]["nodes"].push_back(index);
    }
    return index;
  }
  // Saves .gltf; the buffer goes to `bin_name` next to it, or inline when "".
  std::string save_gltf(const std::string& path, const std::string& bin_name = "") {
    json d = doc;
    if (!bin.empty()) {
      if (bin_name.empty()) {
        d["buffers"] = {{{"byteLength", bin.size()},
                         {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
      } else {
        d["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_name}}};
        write_bytes(std::filesystem::path(path).parent_path() / bin_name, bin);
      }
    }
    std::ofstream(path) << d.dump(1);
    return path;
  }
  std::vector<uint8_t> glb() const {
    json d = doc;
    std::vector<uint8_t> b = bin;
    while (b.size() % 4) b.push_back(0);
    if (!b.empty()) d["buffers"] = {{{"byteLength", b.size()}}};
    std::string text = d.dump();
    while (text.size() % 4) text.push_back(' ');
    std::vector<uint8_t> out;
    const auto u32 = [&](size_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    const size_t total = 20 + text.size() + (b.empty() ? 0 : 8 + b.size());
    out = {'g', 'l', 'T', 'F'};
    u32(2);
    u32(total);
    u32(text.size());
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!b.empty()) {
      u32(b.size());
      u32(0x004E4942);
      out.insert(out.end(), b.begin(), b.end());
    }
    return out;
  }
  std::string save_glb(const std::string& path) const {
    write_bytes(path, glb());
    return path;
  }
};

// The message of the InputError `f` throws ("" and a test failure if none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace sb::test
