#include "scenes/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "scenes/gltf_import.h"

namespace sb::gltf {
namespace {

// Accessors without a bufferView are zeros (plus sparse values): cap them so
// a tiny file cannot ask for gigabytes.
constexpr size_t kMaxUnbackedElements = 16u << 20;

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
}  // namespace

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

std::string accessor_where(int index, const std::string& role) {
  return "accessor " + std::to_string(index) + " (" + role + ")";
}

// Where `count` elements of `element` bytes start at `offset` in bufferView
// `view`; throws unless all of them lie inside the view and its buffer.
AccessorReader::Span AccessorReader::locate(int view, uint64_t offset, uint64_t count,
                                            uint64_t element, bool strided,
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

const tg::Accessor& AccessorReader::accessor(int index, const std::string& role) const {
  if (index < 0 || size_t(index) >= model_.accessors.size())
    fail(role, "accessor " + std::to_string(index) + " does not exist (" +
                   str(model_.accessors.size()) + " accessors)");
  return model_.accessors[size_t(index)];
}

void AccessorReader::check_count(const tg::Accessor& a, const std::string& where) const {
  if (a.count == 0 || a.count > kGltfMaxElements)
    fail(where, "count " + str(a.count) + " is outside [1, " + str(kGltfMaxElements) + "]");
  if (a.bufferView < 0 && a.count > kMaxUnbackedElements)
    fail(where, "count " + str(a.count) + " without a bufferView exceeds the limit of " +
                    str(kMaxUnbackedElements));
}

// Calls write(element index, bytes of one value) for each sparse entry.
template <class F>
void AccessorReader::apply_sparse(const tg::Accessor& a, size_t element, const std::string& where,
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

std::vector<float> AccessorReader::read_floats(int index, int comps,
                                               const std::string& role) const {
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

std::vector<uint32_t> AccessorReader::read_indices(int index, const std::string& role,
                                                   size_t vertices) const {
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
}  // namespace sb::gltf
