#include "scenes/need_providers.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "core/bounded_text.h"
#include "gl/objects.h"
#include "plugin/silhouette_edges.h"
#include "scenes/receiver_inference.h"

namespace sb {

using core::AreaLight;
using core::Bounds;
using core::Mesh;
using core::Scene;
using plugin::CasterAdjacency;
using plugin::CasterEdges;
using plugin::DerivedData;
using plugin::MeshEdge;
using plugin::NeedProvider;
using plugin::PlanarReceiver;
using plugin::SilhouetteEdges;

DerivedDataCounters& derived_data_counters() {
  static DerivedDataCounters counters;
  return counters;
}

bool find_planar_receiver(const Scene& scene, PlanarReceiver& out) {
  const Bounds all = scene.bounds();
  const float eps = 1e-5f * std::max(all.radius(), 1e-6f);
  for (const auto& m : scene.meshes) {
    if (m.triangle_count() == 0) continue;
    const auto plane = mesh_plane(m, double(eps));
    if (!plane) continue;
    glm::vec3 n(*plane);
    auto d = float(plane->w);
    const bool away = scene.light.is_sun() ? glm::dot(n, scene.light.to_sun()) < 0.0f
                                           : glm::dot(n, scene.light.center) + d < 0.0f;
    if (away) {  // orient towards the light
      n = -n;
      d = -d;
    }
    bool below_all = true;
    for (const auto& c : scene.meshes) {
      if (!c.casts_shadow || &c == &m) continue;
      for (const auto& p : c.positions) below_all = below_all && glm::dot(n, p) + d > -eps;
    }
    if (!below_all) continue;
    out.mesh = m.name;
    out.plane = glm::vec4(n, d);
    return true;
  }
  return false;
}

namespace {

glm::vec4 face_plane(const Mesh& m, uint32_t t) {
  const glm::vec3 a = m.positions[m.indices[3 * t]];
  const glm::vec3 b = m.positions[m.indices[3 * t + 1]];
  const glm::vec3 c = m.positions[m.indices[3 * t + 2]];
  glm::vec3 n = glm::cross(b - a, c - a);
  const float len = glm::length(n);
  n = len > 0.0f ? n / len : glm::vec3(0.0f);  // a degenerate face is never a silhouette
  return {n, -glm::dot(n, a)};
}

NeedProvider caster_closedness() {
  NeedProvider p;
  p.name = plugin::need::kCasterClosedness;
  p.summary = "closedness of each caster (boundary, non-manifold, mis-wound edges)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene& scene, DerivedData& data, std::vector<std::string>& log) {
    auto topology = std::make_shared<CasterTopology>();
    size_t open = 0;
    for (const auto& m : scene.meshes) {
      topology->push_back(m.casts_shadow ? analyse_topology(m) : MeshTopology{});
      if (m.casts_shadow) ++derived_data_counters().closedness_checks;
      if (!topology->back().closed()) ++open;
    }
    data.put<CasterTopology>(plugin::need::kCasterClosedness, std::move(topology));
    log.push_back("checked closedness of the casters (" + std::to_string(open) + " open)");
  };
  return p;
}

NeedProvider closed_casters() {
  NeedProvider p;
  p.name = plugin::need::kClosedCasters;
  p.summary = "every caster is a closed 2-manifold (else skipped)";
  p.requires_needs = {plugin::need::kCasterClosedness};
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kClosedCasters);
  };
  p.unmet = [](const Scene& scene, const DerivedData& data) -> std::string {
    const auto& topology = data.get<CasterTopology>(plugin::need::kCasterClosedness);
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
      const auto& m = scene.meshes[i];
      const auto& topo = topology[i];
      if (!m.casts_shadow || topo.closed()) continue;
      std::string what;
      if (topo.boundary_edges) what = std::to_string(topo.boundary_edges) + " boundary edges";
      if (topo.nonmanifold_edges)
        what += (what.empty() ? "" : ", ") + std::to_string(topo.nonmanifold_edges) +
                " non-manifold edges";
      if (topo.inconsistent_edges)
        what += (what.empty() ? "" : ", ") + std::to_string(topo.inconsistent_edges) +
                " inconsistently wound edges";
      return "needs closed casters: mesh " + core::quoted_text(m.name) + " has " + what;
    }
    return "";
  };
  return p;
}

NeedProvider opaque_casters() {
  NeedProvider p;
  p.name = plugin::need::kOpaqueCasters;
  p.summary = "no caster is alpha-tested (else skipped)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kOpaqueCasters);
  };
  p.unmet = [](const Scene& scene, const DerivedData&) -> std::string {
    for (const auto& m : scene.meshes)
      if (m.casts_shadow && m.alpha_tested())
        return "cannot honour alpha masks: mesh " + core::quoted_text(m.name) + " is alpha-tested";
    return "";
  };
  return p;
}

NeedProvider planar_receiver() {
  NeedProvider p;
  p.name = plugin::need::kPlanarReceiver;
  p.summary = "a plane under every caster, receiving all their shadows (else skipped)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene& scene, DerivedData& data, std::vector<std::string>& log) {
    ++derived_data_counters().receiver_searches;
    PlanarReceiver r;
    if (find_planar_receiver(scene, r)) {
      log.push_back("planar receiver: mesh " + core::quoted_text(r.mesh));
      data.put<PlanarReceiver>(plugin::need::kPlanarReceiver, std::make_shared<PlanarReceiver>(r));
    } else {
      log.emplace_back("no planar receiver");
    }
  };
  p.unmet = [](const Scene&, const DerivedData& data) -> std::string {
    return data.find<PlanarReceiver>(plugin::need::kPlanarReceiver) != nullptr
               ? ""
               : "needs a planar receiver under every caster; the scene has none";
  };
  return p;
}

// "a 2×0 segment", "a 1×1 rectangle", "a point": the light as a reason names it.
std::string light_shape(const AreaLight& l) {
  if (l.is_point()) return "a point";
  if (l.is_sun()) {
    std::ostringstream s;
    s << "the sun (" << glm::degrees(l.angular_diameter) << "°)";
    return s.str();
  }
  const auto size = [](float x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  return "a " + size(l.width()) + "×" + size(l.height()) +
         (l.is_segment() ? " segment (a linear light)" : " rectangle");
}

NeedProvider linear_light() {
  NeedProvider p;
  p.name = plugin::need::kLinearLight;
  p.summary = "the light is a segment, light.size [w, 0] or [0, h] (else skipped)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kLinearLight);
  };
  p.unmet = [](const Scene& scene, const DerivedData&) -> std::string {
    if (scene.light.is_segment()) return "";
    return "needs a linear light (a segment: light.size [w, 0] or [0, h]); the scene's light is " +
           light_shape(scene.light);
  };
  return p;
}

NeedProvider rectangular_light() {
  NeedProvider p;
  p.name = plugin::need::kRectangularLight;
  p.summary = "the light is a rectangle or a point, not a segment (else skipped)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kRectangularLight);
  };
  p.unmet = [](const Scene& scene, const DerivedData&) -> std::string {
    if (!scene.light.is_segment()) return "";
    return "needs a rectangular light; the scene's light is " + light_shape(scene.light);
  };
  return p;
}

NeedProvider sun_light() {
  NeedProvider p;
  p.name = plugin::need::kSunLight;
  p.summary = "the light is the sun, light.type \"sun\" (else skipped)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kSunLight);
  };
  p.unmet = [](const Scene& scene, const DerivedData&) -> std::string {
    if (scene.light.is_sun()) return "";
    return "needs the sun (light.type \"sun\"); the scene's light is " + light_shape(scene.light);
  };
  return p;
}

NeedProvider sun_or_local_light() {
  NeedProvider p;
  p.name = plugin::need::kSunOrLocalLight;
  p.summary = "runs under the sun as under a local light";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kSunOrLocalLight);
  };
  return p;
}

NeedProvider local_light() {
  NeedProvider p;
  p.name = plugin::need::kLocalLight;
  p.summary = "the light is at a place, not the sun (else skipped; implied by neither sun need)";
  p.when = NeedProvider::When::Plan;
  p.derive = [](const Scene&, DerivedData& data, std::vector<std::string>&) {
    data.put_check(plugin::need::kLocalLight);
  };
  p.unmet = [](const Scene& scene, const DerivedData&) -> std::string {
    if (!scene.light.is_sun()) return "";
    return "needs a local light (a rectangle, a segment or a point); the scene's light is " +
           light_shape(scene.light);
  };
  return p;
}

NeedProvider edge_adjacency() {
  NeedProvider p;
  p.name = plugin::need::kEdgeAdjacency;
  p.summary = "edge adjacency of the casters";
  p.derive = [](const Scene& scene, DerivedData& data, std::vector<std::string>& log) {
    auto adjacency = std::make_shared<CasterAdjacency>(scene.meshes.size());
    size_t triangles = 0;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
      if (!scene.meshes[i].casts_shadow) continue;
      (*adjacency)[i] = build_adjacency_indices(scene.meshes[i]);
      triangles += scene.meshes[i].triangle_count();
      ++derived_data_counters().adjacency_builds;
    }
    data.put<CasterAdjacency>(plugin::need::kEdgeAdjacency, std::move(adjacency));
    log.push_back("built edge adjacency for " + std::to_string(triangles) + " caster triangles");
  };
  return p;
}

NeedProvider caster_edges() {
  NeedProvider p;
  p.name = plugin::need::kCasterEdges;
  p.summary = "every edge of the casters with the triangles on either side, on the CPU";
  p.derive = [](const Scene& scene, DerivedData& data, std::vector<std::string>& log) {
    auto edges = std::make_shared<CasterEdges>(scene.meshes.size());
    size_t count = 0;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
      if (!scene.meshes[i].casts_shadow) continue;
      (*edges)[i] = mesh_edges(scene.meshes[i]);
      count += (*edges)[i].size();
    }
    data.put<CasterEdges>(plugin::need::kCasterEdges, std::move(edges));
    log.push_back("listed " + std::to_string(count) + " caster edges");
  };
  return p;
}

NeedProvider silhouette_edges() {
  NeedProvider p;
  p.name = plugin::need::kSilhouetteEdges;
  p.summary = "the casters' edges with both faces' planes, in a GPU buffer";
  // Packed and uploaded in one go once a context exists: the CPU copy is
  // not kept.
  p.derive = [](const Scene&, DerivedData&, std::vector<std::string>& log) {
    log.emplace_back("silhouette edges of the casters (uploaded when run)");
  };
  p.upload = [](const Scene& scene, const gl::GpuScene&, DerivedData& data) {
    const SilhouetteEdgeRecords packed = pack_silhouette_edges(scene);
    auto edges = std::make_shared<SilhouetteEdges>();
    edges->edge_count = GLsizei(packed.floats.size() / 16);
    // A zero-sized buffer is not allowed: one unused edge's worth instead.
    const std::vector<float> empty(16, 0.0f);
    const auto& floats = packed.floats.empty() ? empty : packed.floats;
    edges->storage = gl::make_buffer(GLsizeiptr(floats.size() * sizeof(float)), floats.data());
    for (const auto& [first, count] : packed.mesh_ranges)
      edges->meshes.push_back({GLint(first), GLsizei(count)});
    data.put<SilhouetteEdges>(plugin::need::kSilhouetteEdges, std::move(edges));
    ++derived_data_counters().silhouette_uploads;
  };
  return p;
}

}  // namespace

SilhouetteEdgeRecords pack_silhouette_edges(const Scene& scene) {
  SilhouetteEdgeRecords out;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    const int first = int(out.floats.size() / 16);
    if (!m.casts_shadow) {
      out.mesh_ranges.emplace_back(first, 0);
      continue;
    }
    for (const MeshEdge& e : mesh_edges(m)) {
      const glm::vec3 p0 = m.positions[e.v0], p1 = m.positions[e.v1];
      const glm::vec4 a = face_plane(m, e.left);
      const glm::vec4 b = e.right >= 0 ? face_plane(m, uint32_t(e.right)) : glm::vec4(0.0f);
      const float record[16] = {
          p0.x, p0.y, p0.z, float(mi), p1.x, p1.y, p1.z, e.right >= 0 ? 1.0f : 0.0f,
          a.x,  a.y,  a.z,  a.w,       b.x,  b.y,  b.z,  b.w};
      out.floats.insert(out.floats.end(), std::begin(record), std::end(record));
    }
    out.mesh_ranges.emplace_back(first, int(out.floats.size() / 16) - first);
  }
  return out;
}

const std::vector<NeedProvider>& builtin_need_providers() {
  static const std::vector<NeedProvider> providers = {
      caster_closedness(), closed_casters(), opaque_casters(),     planar_receiver(),
      edge_adjacency(),    caster_edges(),   silhouette_edges(),   linear_light(),
      rectangular_light(), sun_light(),      sun_or_local_light(), local_light()};
  return providers;
}

}  // namespace sb
