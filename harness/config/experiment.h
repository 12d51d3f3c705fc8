#pragma once
// An experiment config (docs/config.md), loaded and fully validated before any
// GL context exists. List-valued parameters sweep: each combination becomes
// one variant with a readable name.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json_positions.h"
#include "core/params.h"
#include "core/scene_types.h"
#include "metrics/distance_thirds.h"
#include "metrics/flip.h"
#include "plugin/registry.h"
#include "reference/settings.h"

namespace sb::config {

struct SceneVariant {
  std::string type;     // "sphere_grid"
  std::string name;     // readable variant name: "sphere_grid/light_size=4"
  std::string pointer;  // JSON pointer of its entry, for messages
  // Where its entry is in the config file (load_experiment), for messages
  // about the built scene.
  core::TextPosition position;
  core::Params params;
  nlohmann::json swept = nlohmann::json::object();  // the parameters this variant fixed by sweep
  nlohmann::json light = nlohmann::json::object();  // overrides (validated)
  nlohmann::json camera = nlohmann::json::object();
  // Planar meshes that can shadow nothing become non-casters
  // (scenes/receiver_inference.h); "infer_receivers": false keeps them.
  bool infer_receivers = true;
  // "max_rmse": the stability table's error threshold for this case,
  // instead of the experiment's stability.max_rmse.
  std::optional<double> max_rmse;
};

struct TechniqueVariant {
  const plugin::TechniqueInfo* info = nullptr;
  std::string name;     // readable variant name: "pcf/k=5"
  std::string pointer;  // JSON pointer of its entry
  core::Params params;
  nlohmann::json given = nlohmann::json::object();  // the parameters its entry set, sweeps fixed
  nlohmann::json swept = nlohmann::json::object();  // the parameters this variant fixed by sweep
  // "own_map_size": true: its map size differs from the others' on purpose
  // (config/map_sizes.h leaves it out).
  bool own_map_size = false;
  // Why it cannot run: a name no plugin registered while some plugin failed
  // to load (config/unknown_technique.h). Its jobs fail with this reason and
  // the others run; `info` is then a stand-in that needs nothing, declares
  // no parameter (`params` are as given, unchecked) and cannot be created.
  std::string unavailable;
  std::shared_ptr<const plugin::TechniqueInfo> stand_in;  // owns `info` when unavailable
};

struct Resolution {
  int width = 0;
  int height = 0;
  std::string label() const { return std::to_string(width) + "x" + std::to_string(height); }
  bool operator==(const Resolution&) const = default;
};

struct ReferenceConfig {
  // "method" ("exact" sets settings.exact; "monte_carlo", the default, does
  // not), "spp", "seed", "adaptive", "pilot_spp", "target_std_error" and
  // "embree_config" as given: "" (environment or best ISA), "isa=avx2",
  // "max_isa=avx2". A run may choose another Embree config
  // (run/job_identity.h).
  reference::Settings settings;
  // "second_method": every job is also measured against a reference of the
  // other method (true: exact; false: Monte Carlo), record second_reference.
  std::optional<bool> second_exact;
  bool cache = true;
};

// The "stability" block (docs/stability.md): extra, untimed frames per job
// that measure flicker and parameter sensitivity, and the thresholds of the
// stability table. Absent: no stability figures.
struct StabilityConfig {
  // Frames of a light translated by flicker_step × the casters' bounding-box
  // diagonal per frame along its own u axis; 0 frames turn flicker off, a
  // step of 0 keeps the light still (a technique must then not flicker).
  int flicker_frames = 8;
  double flicker_step = 1.0 / 4096.0;
  // Degraded when the mean flicker exceeds flicker_factor × the reference's
  // own change for the same motion (plus kFlickerFloor).
  double flicker_factor = 2.0;
  // Central differences of every continuous technique parameter and of the
  // light's size, at step sensitivity_step × |p| (× 1 when p is 0).
  bool sensitivity = true;
  double sensitivity_step = 0.01;
  double stiff_threshold = 0.5;  // relative sensitivity above it: stiff
  double max_rmse = 0.1;         // degraded above it (a scene entry may override)
  nlohmann::json to_json() const;
};

// The G-buffer's restore and shading alone: what every frame pays whatever the
// technique.
inline constexpr const char* kDefaultControl = "none";

// "limits": wall-clock budgets of isolated jobs (run --isolation group or
// job; docs/robustness.md). Generous: they catch a hang, not a slow job.
struct RunLimits {
  double job_seconds = 1800;    // one job: prepare, frames, metrics, images
  double setup_seconds = 3600;  // a (scene, resolution)'s scene, G-buffer and reference
};

struct Experiment {
  std::string file;  // as given on the command line
  std::string name;
  std::string description;
  std::vector<SceneVariant> scenes;
  std::vector<TechniqueVariant> techniques;
  std::vector<Resolution> resolutions;
  int warmup_frames = 2;
  int timed_frames = 10;
  // frames.timed "auto": timed_frames (frames.auto_block) frames at a time
  // until the median's 95 % interval is within ± auto_target, at most
  // auto_max_frames frames or auto_max_seconds seconds (run/frame_schedule.h).
  bool timed_auto = false;
  // frames.history: a temporal technique's V (plugin TechniqueInfo::
  // temporal) is measured on this frame of a fresh prepare() of a still
  // scene, whatever its timed frames were.
  int history_frames = 32;
  double auto_target = 0.03;
  int auto_max_frames = 1000;
  double auto_max_seconds = 10;
  // The control job (frames.control): timed next to every job's frames, in
  // the same run, so that a job's time is also known as a ratio to it
  // (record timing.control, docs/ci.md). Absent with "control": null; by
  // default kDefaultControl with its default parameters.
  std::optional<TechniqueVariant> control;
  // frames.noise_threshold: a job whose frame time's (or frame ratio's)
  // median has a 95 % interval wider than ± this fraction is noisy (record
  // timing.noise).
  double noise_threshold = 0.05;
  ReferenceConfig reference;
  std::optional<StabilityConfig> stability;
  // "metrics": {"distance_thirds": true}: the visibility's error also over
  // the near, middle and far third of the camera's distances
  // (metrics/distance_thirds.h), for perspective aliasing.
  bool distance_thirds = false;
  // "metrics": {"distance_scale": "log"}: the thirds of log(distance).
  metrics::DistanceScale distance_scale = metrics::DistanceScale::Linear;
  // "metrics": {"flip_pixels_per_degree": 67.02}: the viewing distance of the
  // FLIP errors (metrics/flip.h), by default the paper's.
  double flip_pixels_per_degree = metrics::kFlipDefaultPixelsPerDegree;
  RunLimits limits;
  std::string content_hash;  // of the file's bytes
  // The registry the techniques came from: the planner finds the providers
  // of plugins' own needs in it (plugin/needs.h).
  const plugin::Registry* registry = nullptr;
  // Where each value is in the file (load_experiment; empty when parsed from
  // JSON alone), so that a problem found later names its line and column.
  std::shared_ptr<const core::JsonPositions> positions;
  core::TextPosition position(const std::string& pointer) const {
    return positions ? positions->find(pointer) : core::TextPosition{};
  }
};

// Caps checked before anything is expanded or built (docs/config.md).
struct ExperimentLimits {
  // scene variants × technique variants × resolutions, counted by
  // multiplying the sweeps' lengths before any is expanded (--max-jobs).
  uint64_t max_jobs = 10000;
};

// Throws InputError naming the file, the line and column, the JSON pointer,
// what was expected and what was found (parse_experiment: no line and column).
Experiment load_experiment(const std::string& path, const plugin::Registry& registry,
                           const ExperimentLimits& limits = {});
Experiment parse_experiment(const nlohmann::json& doc, const std::string& file,
                            const plugin::Registry& registry, const ExperimentLimits& limits = {});

// Applies a scene entry's "light" and "camera" overrides (already validated).
void apply_overrides(const SceneVariant& variant, core::Scene& scene);

// Builds a variant as a run does: the generator (or glTF file), the
// overrides, then core/scene_setup_check.h. A setup that cannot be measured
// (a degenerate camera, coordinates out of range, no proper triangle) throws
// InputError naming `config_file` and the entry's pointer.
core::Scene build_scene(const SceneVariant& variant, const std::string& config_file);

// Cross product of list-valued entries of `params` (an object). Each result
// maps every key to a scalar; `swept` lists the keys that were lists.
std::vector<nlohmann::json> expand_sweeps(const nlohmann::json& params, const std::string& file,
                                          const std::string& pointer);

}  // namespace sb::config
