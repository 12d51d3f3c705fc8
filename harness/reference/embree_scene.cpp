#include "reference/embree_scene.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <glm/glm.hpp>

#include "core/error.h"
#include "reference/ray_offset.h"

namespace sb::reference::detail {

using core::AnalyticShape;
using core::InputError;
using core::JobError;
using core::Mesh;
using core::sample_alpha;
using core::to_string;

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognised error";
}

// Rejects hits on transparent texels of an alpha-tested mesh (both for
// occlusion and for intersection queries).
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* mask = static_cast<const FlatScene::AlphaMask*>(args->geometryUserPtr);
  const Mesh& m = *mask->mesh;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const glm::vec2 uv = (1.0f - u - v) * m.uvs[m.indices[3 * prim]] +
                         u * m.uvs[m.indices[3 * prim + 1]] + v * m.uvs[m.indices[3 * prim + 2]];
    if (sample_alpha(*mask->texture, uv) < m.alpha_cutoff) args->valid[i] = 0;
  }
}

// Lets a ray pass an analytic sphere when it starts on that sphere's own
// mesh: its origin lies within radius + own_tolerance of the centre.
void own_sphere_filter(const RTCFilterFunctionNArguments* args) {
  const auto* sphere = static_cast<const FlatScene::OwnSphere*>(args->geometryUserPtr);
  const double reach = sphere->radius + sphere->own_tolerance;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const glm::dvec3 o(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                       RTCRayN_org_z(args->ray, args->N, i));
    const glm::dvec3 d = o - sphere->center;
    if (glm::dot(d, d) <= reach * reach) args->valid[i] = 0;
  }
}

}  // namespace

Device::Device(const std::string& isa) {
  const std::string config = "isa=" + isa;
  device_ = rtcNewDevice(config.c_str());
  if (!device_)
    throw JobError("Embree: rtcNewDevice(\"" + config +
                   "\") failed: " + error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(device_, &Device::on_error, this);
  // Embree has no query for its ISA, but the native packet widths follow it
  // (4 lanes from sse2, 8 from avx, 16 from avx512): check the device really
  // took the ISA the record and the cache key will name.
  const bool native8 =
      rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
  const bool native16 =
      rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  const bool want8 = isa == "avx" || isa == "avx2" || isa == "avx512", want16 = isa == "avx512";
  if (native8 != want8 || native16 != want16) {
    rtcReleaseDevice(device_);
    throw JobError("Embree: asked for " + config + " but the device's native packets are " +
                   (native16  ? "16"
                    : native8 ? "8"
                              : "4") +
                   " wide");
  }
  // With back-face culling, rays leaving a closed caster from inside would
  // pass through it and light would leak onto its dark side.
  if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED) != 0) {
    rtcReleaseDevice(device_);
    throw JobError("Embree: this build culls back faces; the reference needs it off");
  }
}

Device::~Device() {
  if (device_) rtcReleaseDevice(device_);
}

void Device::on_error(void* self, RTCError code, const char* message) {
  auto* d = static_cast<Device*>(self);
  std::lock_guard<std::mutex> lock(d->mutex_);
  if (d->first_error_.empty())
    d->first_error_ = std::string(error_name(code)) + (message ? std::string(": ") + message : "");
}

void Device::check(const char* what) {
  const RTCError code = rtcGetDeviceError(device_);
  std::string message;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    message.swap(first_error_);
  }
  if (message.empty() && code != RTC_ERROR_NONE) message = error_name(code);
  if (!message.empty()) throw JobError(std::string("Embree: ") + what + ": " + message);
}

void FlatScene::begin(Traversal traversal) {
  scene_ = rtcNewScene(device_.get());
  device_.check("rtcNewScene");
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  // Robust: without it, shadow rays through an edge two caster triangles
  // share can miss both (embree_scene.h; its cost: docs/results.md).
  rtcSetSceneFlags(scene_,
                   traversal == Traversal::Robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
}

void FlatScene::add(const Mesh& mesh, size_t index) {
  const size_t tris = mesh.triangle_count(), verts = mesh.positions.size();
  if (tris == 0) return;
  if (mesh.indices.size() % 3 != 0)
    throw InputError("", "mesh '" + mesh.name + "'", "index count is not a multiple of 3");
  for (uint32_t i : mesh.indices)
    if (i >= verts)
      throw InputError("", "mesh '" + mesh.name + "'",
                       "index " + std::to_string(i) + " >= vertex count " + std::to_string(verts));
  for (const glm::vec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError("", "mesh '" + mesh.name + "'", "non-finite vertex position");

  RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  device_.check("rtcNewGeometry");
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), verts));
  auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tris));
  if (!v || !t) {
    rtcReleaseGeometry(geom);
    device_.check("rtcSetNewGeometryBuffer");
    throw JobError("Embree: rtcSetNewGeometryBuffer returned no buffer");
  }
  std::memcpy(v, mesh.positions.data(), verts * 3 * sizeof(float));
  std::memcpy(t, mesh.indices.data(), tris * 3 * sizeof(uint32_t));
  if (mesh.alpha_tested()) {
    if (mesh.uvs.size() != verts || size_t(mesh.base_color_texture) >= source_.textures.size()) {
      rtcReleaseGeometry(geom);
      throw InputError("", "mesh '" + mesh.name + "'",
                       "alpha-tested without per-vertex uvs or with a missing texture");
    }
    masks_.push_back(std::make_unique<AlphaMask>(
        AlphaMask{&mesh, &source_.textures[size_t(mesh.base_color_texture)]}));
    filter(geom, masks_.back().get(), alpha_filter);
  }
  attach(geom, index, AnalyticShape::Kind::None, "adding a triangle mesh");
}

void FlatScene::add_shape(const Mesh& mesh, size_t index) {
  const AnalyticShape& shape = mesh.analytic;
  if (shape.kind != AnalyticShape::Kind::Sphere)
    throw InputError("", "mesh '" + mesh.name + "'",
                     std::string("analytic shape '") + to_string(shape.kind) +
                         "' is not one the reference traces");
  const glm::vec3 c = shape.center;
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) ||
      !std::isfinite(shape.radius) || !(shape.radius > 0.0f))
    throw InputError("", "mesh '" + mesh.name + "'",
                     "analytic sphere with a non-finite centre or a radius that is not positive");
  if (mesh.alpha_tested())
    throw InputError("", "mesh '" + mesh.name + "'",
                     "an alpha-tested mesh cannot have an analytic shape (the mask has no "
                     "meaning on it)");
  if (rtcGetDeviceProperty(device_.get(), RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED) == 0)
    throw JobError("Embree: this build has no point geometry; analytic spheres need it");

  // The mesh's points lie inside the sphere (its vertices on it, for an
  // inscribed tessellation), and a shadow ray starts at most the ray offset
  // (kOffsetRelative times the point's largest coordinate, itself at most
  // max|c_i| + r) off them: four offsets of room, far below any gap
  // between two shapes of a scene.
  const double largest =
      double(std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)})) + double(shape.radius);
  const OwnSphere own{glm::dvec3(c), double(shape.radius), 4.0 * double(kOffsetRelative) * largest};
  // The rule needs every point of the mesh within the sphere (plus the
  // tolerance): true of an inscribed tessellation, whose vertices lie on it.
  for (const glm::vec3& p : mesh.positions)
    if (glm::length(glm::dvec3(p) - own.center) > own.radius + own.own_tolerance) {
      throw InputError("", "mesh '" + mesh.name + "'",
                       "a vertex lies outside its analytic sphere (the reference needs the "
                       "mesh inside its shape)");
    }
  RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
  device_.check("rtcNewGeometry(sphere)");
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  if (!v) {
    rtcReleaseGeometry(geom);
    device_.check("rtcSetNewGeometryBuffer");
    throw JobError("Embree: rtcSetNewGeometryBuffer returned no buffer");
  }
  v[0] = c.x;
  v[1] = c.y;
  v[2] = c.z;
  v[3] = shape.radius;
  spheres_.push_back(std::make_unique<OwnSphere>(own));
  filter(geom, spheres_.back().get(), own_sphere_filter);
  attach(geom, index, AnalyticShape::Kind::Sphere, "adding an analytic sphere");
}

void FlatScene::filter(RTCGeometry geom, void* data, RTCFilterFunctionN function) {
  rtcSetGeometryUserData(geom, data);
  rtcSetGeometryOccludedFilterFunction(geom, function);
  rtcSetGeometryIntersectFilterFunction(geom, function);
}

void FlatScene::attach(RTCGeometry geom, size_t index, AnalyticShape::Kind kind, const char* what) {
  rtcCommitGeometry(geom);
  const unsigned id = rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  device_.check(what);
  if (mesh_of_geometry.size() <= id) {
    mesh_of_geometry.resize(size_t(id) + 1);
    shape_of_geometry.resize(size_t(id) + 1, AnalyticShape::Kind::None);
  }
  mesh_of_geometry[id] = index;
  shape_of_geometry[id] = kind;
}

void FlatScene::commit() {
  rtcCommitScene(scene_);
  device_.check("rtcCommitScene");
}

FlatScene::~FlatScene() {
  if (scene_) rtcReleaseScene(scene_);
}

FtzDazScope::FtzDazScope() : saved_(_mm_getcsr()) {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

FtzDazScope::~FtzDazScope() { _mm_setcsr(saved_); }

}  // namespace sb::reference::detail
