#include "run/scene_upload.h"

#include <utility>
#include <vector>

#include "gl/allocation_meter.h"
#include "scenes/need_providers.h"
#include "scenes/receiver_inference.h"

namespace sb::run {

using core::Mesh;
using gl::GpuScene;
using gl::MeshDrawFlags;
using plan::ScenePlan;
using plugin::CasterAdjacency;
using plugin::DerivedData;
using plugin::NeedProvider;

namespace {

// Per mesh: closed (depth passes may cull it; known when a technique in the
// plan asked for closedness) and, for receivers, whether nothing lies behind
// them from the light (filtered maps may draw them).
std::vector<MeshDrawFlags> draw_flags(const ScenePlan& st) {
  std::vector<MeshDrawFlags> flags(st.scene.meshes.size());
  const auto* topology = st.derived.find<CasterTopology>(plugin::need::kCasterClosedness);
  const ShadowNothingTest shadows_nothing(st.scene);
  for (size_t i = 0; i < flags.size(); ++i) {
    const Mesh& m = st.scene.meshes[i];
    flags[i].closed = m.casts_shadow && topology != nullptr && (*topology)[i].closed();
    flags[i].nothing_behind = !m.casts_shadow && shadows_nothing(i);
  }
  return flags;
}

}  // namespace

UploadedScene upload_scene(const ScenePlan& st) {
  const auto* adjacency = st.derived.find<CasterAdjacency>(plugin::need::kEdgeAdjacency);
  auto uploaded = std::make_unique<GpuScene>(st.scene, adjacency ? *adjacency : CasterAdjacency{},
                                             draw_flags(st));
  std::map<std::string, std::int64_t> need_gpu_bytes;
  if (adjacency != nullptr)
    need_gpu_bytes[plugin::need::kEdgeAdjacency] = uploaded->adjacency_bytes();
  DerivedData with_gpu = st.derived;
  for (const NeedProvider* p : st.uploads) {
    const gl::AllocationWindow window;
    p->upload(st.scene, *uploaded, with_gpu);
    need_gpu_bytes[p->name] = window.live_bytes();  // what it keeps, not its scratch
  }
  return {std::move(uploaded), std::move(with_gpu), std::move(need_gpu_bytes)};
}

std::map<std::string, std::int64_t> UploadedScene::gpu_bytes_held_for(
    const std::vector<std::string>& needs) const {
  std::map<std::string, std::int64_t> out;
  for (const std::string& n : needs)
    if (const auto it = need_gpu_bytes.find(n); it != need_gpu_bytes.end()) out.insert(*it);
  return out;
}

}  // namespace sb::run
