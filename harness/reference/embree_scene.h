#pragma once
// RAII around an Embree device and a flat scene of triangles and, for meshes
// with an analytic shape (Mesh::analytic), of that shape (internal).
#include <embree3/rtcore.h>

#include <cstdint>
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

// How Embree meets rays that pass through an edge or a vertex shared by
// neighbouring triangles. Robust (RTC_SCENE_FLAG_ROBUST, every scene of the
// harness): conservative traversal and no arithmetic shortcuts, meant for
// exactly those rays; in tests/reference/test_reference_watertight.cpp none
// slips through (Embree promises no watertightness for every ray, see
// embree/embree#387). Fast (Embree's default) lets some slip between both
// triangles: light leaking through a closed or tessellated caster, single
// rays in an umbra. Fast is there only to show what robustness costs and
// changes (bench_reference, that test).
enum class Traversal : uint8_t { Robust, Fast };

class FlatScene {
 public:
  // Every mesh for which `take(mesh)` is true becomes one geometry
  // (flattened: no instances): its triangles, or with `analytic_shapes` and
  // a mesh that has one, its analytic shape. mesh_of_geometry maps geomID to
  // mesh index, shape_of_geometry to what that geometry is.
  template <typename Pred>
  FlatScene(Device& device, const core::Scene& scene, Pred take, bool analytic_shapes = false,
            Traversal traversal = Traversal::Robust)
      : device_(device), source_(scene) {
    begin(traversal);
    try {
      for (size_t i = 0; i < scene.meshes.size(); ++i) {
        if (!take(scene.meshes[i])) continue;
        if (analytic_shapes && scene.meshes[i].analytic.has())
          add_shape(scene.meshes[i], i);
        else
          add(scene.meshes[i], i);
      }
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
  std::vector<core::AnalyticShape::Kind> shape_of_geometry;  // None: the mesh's triangles

  // What an alpha-tested geometry's filter needs: the mesh (uvs, indices)
  // and its texture. Hits on texels below the cutoff are rejected, exactly
  // where the rasteriser discards (sample_alpha, nearest texel).
  struct AlphaMask {
    const core::Mesh* mesh;
    const core::TextureImage* texture;
  };

  // What an analytic sphere's filter needs. A ray whose origin lies within
  // radius + own_tolerance of the centre starts on (or in) this sphere's own
  // mesh, and the sphere does not occlude it (reference.h says why).
  struct OwnSphere {
    glm::dvec3 center;
    double radius;
    double own_tolerance;
  };

 private:
  void begin(Traversal traversal);
  void add(const core::Mesh& mesh, size_t index);
  void add_shape(const core::Mesh& mesh, size_t index);
  // Both queries' filter, with its data.
  static void filter(RTCGeometry geom, void* data, RTCFilterFunctionN function);
  // Commits geom, attaches it as mesh `index` (of `kind`) and releases it.
  void attach(RTCGeometry geom, size_t index, core::AnalyticShape::Kind kind, const char* what);
  void commit();
  Device& device_;
  const core::Scene& source_;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<AlphaMask>> masks_;
  std::vector<std::unique_ptr<OwnSphere>> spheres_;
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
