#pragma once
// record["scene"] and record["technique"]: what ran (docs/results.md).
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/fields.h"

namespace sb {

struct LightRecord {
  std::array<double, 3> center{}, target{};
  std::array<double, 2> size{};  // width, height of the rectangle
  double intensity = 1;
};

struct CameraRecord {
  std::array<double, 3> eye{}, target{};
  double fov_y = 45;  // degrees
};

// Derived data the plan computed for the scene, and its receiver inference.
struct DerivedRecord {
  bool closedness_checked = false;
  bool adjacency_built = false;
  bool receiver_inference = true;               // off with "infer_receivers": false
  std::vector<std::string> inferred_receivers;  // meshes made receivers
};

// What is known of a scene once it was built: absent from the records of a
// scene that failed to build.
struct BuiltScene {
  std::int64_t triangles = 0;
  std::int64_t caster_triangles = 0;
  // Casters the reference traces as their analytic shape instead of their
  // triangles (Mesh::analytic; records before it have none).
  std::int64_t analytic_casters = 0;
  LightRecord light;
  CameraRecord camera;
  DerivedRecord derived;
};

struct SceneRecord {
  std::string type;
  std::string variant;
  nlohmann::json params = nlohmann::json::object();  // all, defaults filled in
  std::optional<BuiltScene> built;

  nlohmann::json to_json() const;
  static SceneRecord from_json(const Fields& f);
};

// technique.plugin: the module the technique came from (plugin/plugin_identity.h).
struct PluginRecord {
  std::string file;  // relative to its plugin folder: "shadow_map.so"
  std::int64_t size = 0;
  std::string sha256;  // of the module's bytes
  int api_version = 0;

  bool operator==(const PluginRecord&) const = default;
  nlohmann::json to_json() const;
  static PluginRecord from_json(const Fields& f);
};

struct TechniqueRecord {
  std::string name;
  std::string family;
  std::string variant;
  nlohmann::json params = nlohmann::json::object();  // all, defaults filled in
  // Absent in records from before plugin identities, and for a technique
  // no module registered (a test's own).
  std::optional<PluginRecord> plugin;
  // The most bytes of GPU storage the technique held at once, from its
  // prepare() to its last frame, as made through the gl::make_* helpers
  // (gl/allocation_meter.h). Absent from older records and from jobs that
  // did not get through their frames.
  std::optional<std::int64_t> gpu_bytes;

  nlohmann::json to_json() const;
  static TechniqueRecord from_json(const Fields& f);
};

}  // namespace sb
