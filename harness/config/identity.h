#pragma once
// The parts of a job's identity (the spec a rerun compares,
// run/job_identity.h) that the config describes, each generated from the
// declarations where the setting is described: a parameter's
// ParamSpec::decides, a config block key's (config/config_blocks.h). A
// setting that decides no number is left out; a file is identified by its
// content (SHA-256), never by the path that named it.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "core/params.h"
#include "core/scene.h"

namespace sb::config {

// A file parameter's identity: {"sha256": its bytes' hash} and, when the
// scene read more files through it (a glTF file's buffers and images),
// "reads": {their name relative to its folder: their hash}. The hashes come
// from `inputs` (what building the scene read) where it holds the file, else
// from reading the file now; a file that cannot be read is {"sha256": null}.
nlohmann::json file_identity(const std::string& path, const std::vector<core::InputFile>& inputs);

// The parameters that decide some number, by name; path parameters as
// file_identity. Without specs (a technique whose plugin did not load), all
// of them as given.
nlohmann::json params_identity(const std::vector<core::ParamSpec>& specs,
                               const core::Params& params,
                               const std::vector<core::InputFile>& inputs = {});

// A technique variant: its name, params_identity and its plugin module's
// identity (file, sha256, api_version: a rebuilt plugin reruns), when a
// module registered it.
nlohmann::json technique_identity(const Experiment& e, const TechniqueVariant& tv);

// A key of a scene entry beside "type" and "params" (docs/config.md, "Scene
// entries"), with what it decides and its value in a variant.
struct SceneEntryKey {
  std::string name;
  core::Decides decides;
  // The variant's value, as its part of the identity; null for a key that
  // decides nothing.
  std::function<nlohmann::json(const SceneVariant&)> value;
  nlohmann::json example;  // a valid value other than the default, for tests
};

// light, camera, label, infer_receivers, max_rmse: the keys a scene entry
// may have besides "type" and "params" (the config reader accepts these).
const std::vector<SceneEntryKey>& scene_entry_keys();

// A scene variant: its type, params_identity (with `inputs`, what building
// it read) and the entry's keys that decide some number.
nlohmann::json scene_identity(const SceneVariant& sv, const std::vector<core::InputFile>& inputs);

// Every config block's keys that decide some number, as named fields:
// {"frames": {"warmup": 2, ...}, "reference": {...}, "stability": null, ...};
// a block not in effect (stability when absent) is null, a block none of
// whose keys decides a number (limits) is left out.
nlohmann::json blocks_identity(const Experiment& e);

}  // namespace sb::config
