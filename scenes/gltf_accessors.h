#pragma once
// Bounds-checked reading of accessor data. An accessor says "count elements
// of this type, from this offset of that bufferView", and a hostile file can
// make any of it lie: a 1 KB file may claim 3e8 elements. Counts are capped
// before anything is allocated, every element is located inside its
// bufferView and buffer before it is read, sparse substitutions are checked
// entry by entry, and the values read must be finite.
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/gltf_common.h"

namespace sb::gltf {

// Bytes per component, 0 for what glTF 2.0 accessors do not allow.
int component_size(int component_type);
// "accessor 3 (POSITION of mesh 'car' (0) primitive 0)".
std::string accessor_where(int index, const std::string& role);

class AccessorReader : public ImportStep {
 public:
  AccessorReader(const std::string& file, const tg::Model& model)
      : ImportStep(file), model_(model) {}

  // `role` says what the accessor is for, in the message when it does not exist.
  const tg::Accessor& accessor(int index, const std::string& role) const;
  void check_count(const tg::Accessor& a, const std::string& where) const;
  // A VEC2/VEC3 attribute as floats, any component type (normalised or not).
  std::vector<float> read_floats(int index, int comps, const std::string& role) const;
  // Indices, each checked against the vertex count.
  std::vector<uint32_t> read_indices(int index, const std::string& role, size_t vertices) const;

 private:
  struct Span {
    const unsigned char* data = nullptr;
    size_t stride = 0;
  };
  Span locate(int view, uint64_t offset, uint64_t count, uint64_t element, bool strided,
              const std::string& where) const;
  template <class F>
  void apply_sparse(const tg::Accessor& a, size_t element, const std::string& where,
                    F&& write) const;

  const tg::Model& model_;
};

}  // namespace sb::gltf
