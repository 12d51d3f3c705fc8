#pragma once
// RAII around an Embree device and a flat triangle scene (internal).
#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/scene.h"

namespace sb::reference::detail {

// Embree reports errors through a callback; they are collected here and
// turned into sb::JobError by check() after each API call that can fail.
class Device {
 public:
  // A device on exactly `isa` (one of embree_isas(), resolved by
  // resolve_isa). Throws sb::JobError if Embree's kernels turn out to be of
  // another width than that ISA's.
  explicit Device(const std::string& isa);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  RTCDevice get() const { return device_; }
  void check(const char* what);  // throws sb::JobError on a pending error

 private:
  static void on_error(void* self, RTCError code, const char* message);
  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  std::string first_error_;
};

class FlatScene {
 public:
  // Every mesh for which `take(mesh)` is true becomes one triangle geometry
  // (flattened: no instances). mesh_of_geometry maps geomID to mesh index.
  template <typename Pred>
  FlatScene(Device& device, const Scene& scene, Pred take) : device_(device), source_(scene) {
    begin();
    try {
      for (size_t i = 0; i < scene.meshes.size(); ++i)
        if (take(scene.meshes[i])) add(scene.meshes[i], i);
      commit();
    } catch (...) {
      rtcReleaseScene(scene_);  // the destructor does not run for a throwing constructor
      throw;
    }
  }
  ~FlatScene();
  FlatScene(const FlatScene&) = delete;
  FlatScene& operator=(const FlatScene&) = delete;

  RTCScene get() const { return scene_; }
  bool empty() const { return mesh_of_geometry.empty(); }
  std::vector<size_t> mesh_of_geometry;

  // What an alpha-tested geometry's filter needs: the mesh (uvs, indices)
  // and its texture. Hits on texels below the cutoff are rejected, exactly
  // where the rasteriser discards (sample_alpha, nearest texel).
  struct AlphaMask {
    const Mesh* mesh;
    const TextureImage* texture;
  };

 private:
  void begin();
  void add(const Mesh& mesh, size_t index);
  void commit();
  Device& device_;
  const Scene& source_;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<AlphaMask>> masks_;
};

// Sets flush-to-zero and denormals-are-zero for the current thread (Embree
// wants them on every thread that traces) and restores the previous mode.
class FtzDazScope {
 public:
  FtzDazScope();
  ~FtzDazScope();
  FtzDazScope(const FtzDazScope&) = delete;
  FtzDazScope& operator=(const FtzDazScope&) = delete;

 private:
  unsigned int saved_;
};

}  // namespace sb::reference::detail
