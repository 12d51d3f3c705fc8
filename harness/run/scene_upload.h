#pragma once
// A planned scene on the GPU: its meshes uploaded once per process, with
// the draw flags its depth passes may use, and the GPU stages of the running
// techniques' needs (plugin/needs.h) run over it.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/gpu_scene.h"
#include "plan/plan.h"
#include "plugin/derived_data.h"

namespace sb::run {

struct UploadedScene {
  std::unique_ptr<gl::GpuScene> gpu;
  plugin::DerivedData derived;  // the plan's, and the GPU stages' (free it before gpu)
  // Per need the harness put on the GPU (need::kEdgeAdjacency's index
  // buffer, each provider's upload): the bytes of storage it holds, as the
  // meter counts a technique's own (gl/allocation_meter.h).
  std::map<std::string, std::int64_t> need_gpu_bytes;

  // The entries of need_gpu_bytes among `needs` (a technique's, with what
  // they require: plan::ScenePlan::needs), which its job is charged.
  std::map<std::string, std::int64_t> gpu_bytes_held_for(
      const std::vector<std::string>& needs) const;
};

// Both or neither: throws when the upload or a GPU stage fails.
UploadedScene upload_scene(const plan::ScenePlan& st);

}  // namespace sb::run
