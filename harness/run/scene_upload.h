#pragma once
// A planned scene on the GPU: its meshes uploaded once per process, with
// the draw flags its depth passes may use, and the GPU stages of the running
// techniques' needs (plugin/needs.h) run over it.
#include <memory>

#include "gl/gpu_scene.h"
#include "plan/plan.h"
#include "plugin/derived_data.h"

namespace sb::run {

struct UploadedScene {
  std::unique_ptr<gl::GpuScene> gpu;
  plugin::DerivedData derived;  // the plan's, and the GPU stages' (free it before gpu)
};

// Both or neither: throws when the upload or a GPU stage fails.
UploadedScene upload_scene(const plan::ScenePlan& st);

}  // namespace sb::run
