#pragma once
// Needs: the data a technique asks the planner to derive from a scene, by
// name, before any GL context exists. Each name is resolved by a provider
// (NeedProvider) that declares what it computes; nothing is computed unless
// some technique in the plan asked for it. The harness provides the needs in
// `need::` below; a plugin adds a need by registering a provider with
// Registry::add_provider, without editing the harness.
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/scene.h"
#include "plugin/derived_data.h"

namespace sb::gl {
class GpuScene;
}  // namespace sb::gl

namespace sb::plugin {

// The needs the harness provides, and what each gives the technique.
namespace need {
// Which casters are closed 2-manifolds (no skip): depth passes cull only
// closed ones. Data: none a technique reads (GpuScene's DrawInfo.cullable).
inline constexpr const char* kCasterClosedness = "caster_closedness";
// Every caster is a closed 2-manifold, else the job is skipped.
inline constexpr const char* kClosedCasters = "closed_casters";
// No caster is alpha-tested, else the job is skipped.
inline constexpr const char* kOpaqueCasters = "opaque_casters";
// A plane that receives every caster's shadow, else the job is skipped.
// Data: FrameInputs::receiver_plane, and PlanarReceiver (plugin/need_data.h).
inline constexpr const char* kPlanarReceiver = "planar_receiver";
// GL_TRIANGLES_ADJACENCY indices of the casters: GpuScene::draw_casters_adjacency
// (CasterAdjacency).
inline constexpr const char* kEdgeAdjacency = "edge_adjacency";
// Every edge of the casters once with the triangles on either side
// (MeshEdge), on the CPU. Data: CasterEdges.
inline constexpr const char* kCasterEdges = "caster_edges";
// An SSBO of the casters' edges, each with the planes of its two faces
// (plugin/silhouette_edges.h), so a shader can find silhouettes without
// uploading the scene again. Data: SilhouetteEdges.
inline constexpr const char* kSilhouetteEdges = "silhouette_edges";
// The light is a segment (a linear light: light.size [w, 0] or [0, h]), else
// the job is skipped. Data: none (AreaLight::segment_end gives its ends).
inline constexpr const char* kLinearLight = "linear_light";
// The light is a rectangle or a point, not a segment, else the job is
// skipped: for techniques whose filter or integral assumes the light's
// rectangle has both sides (docs/linear_lights.md says which and why).
inline constexpr const char* kRectangularLight = "rectangular_light";
// The light is the sun (light.type "sun": a directional light with an
// angular size; core::AreaLight::is_sun), else the job is skipped: for
// techniques made for it alone (cascaded shadow maps). Data: none.
inline constexpr const char* kSunLight = "sun_light";
// The technique runs under the sun as under a local light. Data: none.
inline constexpr const char* kSunOrLocalLight = "sun_or_local_light";
// The light is local (a rectangle, a segment or a point), else the job is
// skipped. Every technique that names neither need above has this one
// without naming it: a technique written for a light at a place is never
// run under the sun by accident. Data: none.
inline constexpr const char* kLocalLight = "local_light";
}  // namespace need

// A technique's needs, in the order it wants them checked: the first unmet
// one is the reason its job is skipped.
struct Needs {
  std::vector<std::string> names;
  Needs() = default;
  Needs(std::initializer_list<std::string> list) : names(list) {}
  bool has(const std::string& name) const;
};

// Computes one need for one scene.
struct NeedProvider {
  std::string name;     // what techniques ask for
  std::string summary;  // one line for `shadowbench list` and the plan
  // Needs computed before this one (their data is in `derive`'s DerivedData).
  std::vector<std::string> requires_needs;
  // Plan: computed for every technique of the experiment that asked, before
  // the skip decisions, also by `plan` and `validate` (keep it cheap; only a
  // Plan need may skip a job). Run: computed only for techniques that will
  // run, and only when running.
  enum class When { Plan, Run } when = When::Run;
  // CPU, no GL: puts its data into `data` under `name` (or nothing, for a
  // pure check) and says what it did in `log`.
  std::function<void(const core::Scene&, DerivedData& data, std::vector<std::string>& log)> derive;
  // Optional: "" when the scene meets the need, else why not, worded to
  // follow the technique's name ("needs closed casters: mesh 'x' ...").
  std::function<std::string(const core::Scene&, const DerivedData&)> unmet = nullptr;
  // Optional, GPU: once per scene after its upload, with a current context;
  // puts GL resources into `data` (freed with it, in the same context).
  std::function<void(const core::Scene&, const gl::GpuScene&, DerivedData& data)> upload = nullptr;
};

}  // namespace sb::plugin
