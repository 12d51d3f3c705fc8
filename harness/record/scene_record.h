#pragma once
// record["scene"] and record["technique"]: what ran (docs/results.md).
#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

struct LightRecord {
  static constexpr RecordDoc kSchema{
      "LightRecord", "the scene's light: a rectangle (a segment, a point) or the sun"};

  std::array<double, 3> center{}, target{};
  std::array<double, 2> size{};  // width, height of the rectangle
  double intensity = 1;
  std::optional<double> angular_diameter;  // degrees; the sun's only

  template <class V>
  static void describe(V& v) {
    v.field("center", &LightRecord::center, {"", "[x, y, z]"});
    v.field("target", &LightRecord::target, {"", "[x, y, z] it faces"});
    v.field("size", &LightRecord::size, {"", "[width, height] of the rectangle"});
    v.field("intensity", &LightRecord::intensity,
            {"", "scales the light's term in the shaded image (V never depends on it)"});
    v.field("angular_diameter", &LightRecord::angular_diameter,
            {"degrees",
             "present for the sun only (light.type \"sun\"), a disk at infinity seen from "
             "center towards target; its center is then only a place on the sun's side, and "
             "size the disk's diameter at center's distance"});
  }
};

struct CameraRecord {
  static constexpr RecordDoc kSchema{"CameraRecord", "the scene's camera"};

  std::array<double, 3> eye{}, target{};
  double fov_y = 45;  // degrees

  template <class V>
  static void describe(V& v) {
    v.field("eye", &CameraRecord::eye, {"", "[x, y, z]"});
    v.field("target", &CameraRecord::target, {"", "[x, y, z] it looks at"});
    v.field("fov_y", &CameraRecord::fov_y, {"degrees", "vertical field of view"});
  }
};

// Derived data the plan computed for the scene, and its receiver inference.
struct DerivedRecord {
  static constexpr RecordDoc kSchema{"DerivedRecord",
                                     "derived data the plan computed for the scene"};

  bool closedness_checked = false;
  bool adjacency_built = false;
  bool receiver_inference = true;               // off with "infer_receivers": false
  std::vector<std::string> inferred_receivers;  // meshes made receivers

  template <class V>
  static void describe(V& v) {
    using D = DerivedRecord;
    v.field("closedness_checked", &D::closedness_checked,
            {"", "the casters' closedness was derived: a technique running on the scene needs it"});
    v.field(
        "adjacency_built", &D::adjacency_built,
        {"", "the casters' edge adjacency was built: a technique running on the scene needs it"});
    v.field("receiver_inference", &D::receiver_inference,
            {"", "on unless the scene entry says `\"infer_receivers\": false`"});
    v.field("inferred_receivers", &D::inferred_receivers,
            {"",
             "planar meshes made non-casters because they can shadow nothing "
             "(docs/design.md)"});
  }
};

// What is known of a scene once it was built: absent from the records of a
// scene that failed to build.
struct BuiltScene {
  static constexpr RecordDoc kSchema{"BuiltScene", ""};

  std::int64_t triangles = 0;
  std::int64_t caster_triangles = 0;
  // Casters the reference traces as their analytic shape instead of their
  // triangles (Mesh::analytic; records before it have none).
  std::int64_t analytic_casters = 0;
  LightRecord light;
  CameraRecord camera;
  DerivedRecord derived;

  template <class V>
  static void describe(V& v) {
    v.field("triangles", &BuiltScene::triangles, {"", "the scene's triangles"});
    v.field("caster_triangles", &BuiltScene::caster_triangles, {"", "those that cast"});
    v.field("analytic_casters", &BuiltScene::analytic_casters,
            {"",
             "casters the reference traces as their smooth shape (a sphere grid's "
             "`\"analytic\": true`); absent from older records, read as 0",
             Presence::OlderLack});
    v.field("light", &BuiltScene::light, {"", "the light"});
    v.field("camera", &BuiltScene::camera, {"", "the camera"});
    v.field("derived", &BuiltScene::derived, {"", "what the plan derived"});
  }
};

struct SceneRecord {
  static constexpr RecordDoc kSchema{"SceneRecord", "the scene that ran"};

  std::string type;
  std::string variant;
  nlohmann::json params = nlohmann::json::object();  // all, defaults filled in
  std::optional<BuiltScene> built;

  template <class V>
  static void describe(V& v) {
    v.field("type", &SceneRecord::type, {"", "the scene type"});
    v.field("variant", &SceneRecord::variant, {"", "the scene variant"});
    v.field("params", &SceneRecord::params, {"", "all its parameters, defaults filled in"});
    v.flatten(&SceneRecord::built, {"", "when the scene was built"});
  }

  nlohmann::json to_json() const;
  static SceneRecord from_json(const Fields& f);
};

// technique.plugin: the module the technique came from (plugin/plugin_identity.h).
struct PluginRecord {
  static constexpr RecordDoc kSchema{
      "PluginRecord", "the module that registered the technique (built-in families too)"};

  std::string file;  // relative to its plugin folder: "shadow_map.so"
  std::int64_t size = 0;
  std::string sha256;  // of the module's bytes
  int api_version = 0;

  template <class V>
  static void describe(V& v) {
    v.field("file", &PluginRecord::file, {"", "the module's name in its plugin folder"});
    v.field("size", &PluginRecord::size, {"bytes", "of the module's file"});
    v.field("sha256", &PluginRecord::sha256, {"", "of its bytes, read once when it is loaded"});
    v.field("api_version", &PluginRecord::api_version,
            {"", "`kPluginApiVersion` (harness/plugin/plugin_identity.h): the plugin ABI's"});
  }

  bool operator==(const PluginRecord&) const = default;
  nlohmann::json to_json() const;
  static PluginRecord from_json(const Fields& f);
};

struct TechniqueRecord {
  static constexpr RecordDoc kSchema{"TechniqueRecord", "the technique that ran"};

  std::string name;
  std::string family;
  std::string variant;
  nlohmann::json params = nlohmann::json::object();  // all, defaults filled in
  // Absent in records from before plugin identities, and for a technique
  // no module registered (a test's own).
  std::optional<PluginRecord> plugin;
  // GPU storage (docs/results.md, "GPU memory"): the most the technique
  // held at once from its prepare() to its last frame, made through the
  // gl::make_* helpers (gl/allocation_meter.h), and what the harness holds
  // on the GPU for the needs it declares (edge adjacency, silhouette edges,
  // a plugin need's upload), per need. gpu_bytes is their sum. Absent from
  // jobs that did not get through their frames and from failed jobs (theirs
  // are in JobRecord::partial); the parts are absent from older records,
  // whose gpu_bytes is the technique's own only.
  std::optional<std::int64_t> gpu_bytes;
  std::optional<std::int64_t> gpu_own_bytes;
  std::optional<std::map<std::string, std::int64_t>> gpu_need_bytes;
  // A temporal technique's: the frame after a fresh prepare() whose V was
  // measured (frames.history). Absent for the others.
  std::optional<std::int64_t> measured_frame;

  // Sets the parts and their sum.
  void set_gpu_bytes(std::int64_t own, const std::map<std::string, std::int64_t>& needs);
  // gpu_bytes when the record has its parts: its total. nullopt for older
  // records, whose gpu_bytes left the needs out.
  std::optional<std::int64_t> gpu_total_bytes() const;

  template <class V>
  static void describe(V& v) {
    using T = TechniqueRecord;
    v.field("name", &T::name, {"", "the technique"});
    v.field("family", &T::family, {"", "its family"});
    v.field("variant", &T::variant, {"", "the technique variant"});
    v.field("params", &T::params, {"", "all its parameters, defaults filled in"});
    v.field("plugin", &T::plugin,
            {"", "absent from older records and for a technique no module registered"});
    v.field("gpu_bytes", &T::gpu_bytes,
            {"bytes",
             "the technique's GPU memory: `gpu_own_bytes` plus the sum of `gpu_need_bytes` "
             "(below); absent from jobs that failed before their last frame and from failed "
             "jobs (a failed job's are under `partial`); in records without `gpu_own_bytes`, "
             "its own storage only"});
    v.field("gpu_own_bytes", &T::gpu_own_bytes,
            {"bytes",
             "the most GPU storage the technique held at once from its `prepare()` to its "
             "last frame, made through the `gl::make_*` helpers (\"GPU memory\" above); absent "
             "from older records"});
    v.field("gpu_need_bytes", &T::gpu_need_bytes,
            {"bytes",
             "per need the technique declares (with those they require) that the harness "
             "holds on the GPU for it, the bytes it holds: `edge_adjacency`, "
             "`silhouette_edges`, a plugin need's upload; `{}` when none; absent from older "
             "records"});
    v.field("measured_frame", &T::measured_frame,
            {"",
             "a temporal technique's (one whose frames depend on the frames before them): its "
             "V, its errors and its stability figures come from this frame of a fresh "
             "`prepare()` on the still scene (`frames.history`); absent for the others"});
  }

  // gpu_bytes is the sum of its parts, when they are there.
  static void check(const TechniqueRecord& t, const Fields& f);

  nlohmann::json to_json() const;
  static TechniqueRecord from_json(const Fields& f);
};

}  // namespace sb::record
