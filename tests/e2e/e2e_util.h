#pragma once
// Runs small experiments through the real driver code path and reads back
// what they wrote.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "run/runner.h"

namespace sb::test {

struct RunOutput {
  std::string dir;
  run::RunSummary summary;
  std::vector<nlohmann::json> records;
  const nlohmann::json& record(const std::string& technique_variant) const;
  core::ImageF visibility(const std::string& technique_variant) const;
  core::ImageF reference_visibility() const;  // of the first record
  core::ImageF gbuffer_positions() const;     // of the first record (write_gbuffer runs)
  // Any image a record names under "images" (e.g. "visibility", "gbuffer_positions").
  core::ImageF image(const nlohmann::json& record, const std::string& key) const;
  // The mask of a region the record names under "images.masks": 1 where
  // the PNG is 255.
  std::vector<uint8_t> mask(const nlohmann::json& record, const std::string& region) const;
};

// `config` is an experiment JSON; `name` picks a fresh folder under /tmp.
RunOutput run_config(const nlohmann::json& config, const std::string& name,
                     gl::Backend backend = gl::Backend::OSMesa, bool fresh = true,
                     bool write_gbuffer = false);
// The same, with the run's options adjusted before it starts.
RunOutput run_config_with(const nlohmann::json& config, const std::string& name,
                          const std::function<void(run::RunOptions&)>& adjust, bool fresh = true);

// Runs `config` against `registry` (test techniques registered in the test),
// without images or a reference cache, into a fresh folder named `name`.
RunOutput run_with_registry(const nlohmann::json& config, const plugin::Registry& registry,
                            const std::string& name);

// Pixels on the ground plane y = 0 (the sphere grid's and the test scenes'),
// from a run's G-buffer positions.
std::vector<bool> ground_pixels(const core::ImageF& positions);

// A small sphere grid seen from close by, for fast runs.
nlohmann::json small_scene(double light_size);

// `name` in the temporary folder, suffixed with this process's id: ctest runs
// the shards of one test executable at once, and a suite's SetUpTestSuite runs
// in every shard that holds one of its tests (CI failed on a shared folder).
std::string process_temp_path(const std::string& name);

// An empty folder named for the running test and this process.
std::string fresh_test_folder(const std::string& prefix);

}  // namespace sb::test
