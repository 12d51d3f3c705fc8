#include "scenes/topology.h"

#include <algorithm>
#include <unordered_map>

namespace sb {

using core::Mesh;
using plugin::MeshEdge;

namespace {

// Maps every vertex to the first vertex with the same position.
std::vector<uint32_t> weld_by_position(const Mesh& mesh) {
  struct Hash {
    size_t operator()(const glm::vec3& p) const {
      const auto h = [](float f) { return std::hash<float>()(f); };
      return h(p.x) * 73856093u ^ h(p.y) * 19349663u ^ h(p.z) * 83492791u;
    }
  };
  std::unordered_map<glm::vec3, uint32_t, Hash> first;
  first.reserve(mesh.positions.size());
  std::vector<uint32_t> canonical(mesh.positions.size());
  for (uint32_t i = 0; i < mesh.positions.size(); ++i)
    canonical[i] = first.emplace(mesh.positions[i], i).first->second;
  return canonical;
}

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

struct DirectedEdges {
  // directed edge (a,b) -> (triangle, corner opposite the edge)
  std::unordered_multimap<uint64_t, std::pair<uint32_t, uint32_t>> map;
};

DirectedEdges directed_edges(const Mesh& mesh, const std::vector<uint32_t>& w) {
  DirectedEdges d;
  d.map.reserve(mesh.indices.size());
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = w[mesh.indices[3 * t + e]];
      const uint32_t b = w[mesh.indices[3 * t + (e + 1) % 3]];
      d.map.emplace(edge_key(a, b), std::make_pair(t, mesh.indices[3 * t + (e + 2) % 3]));
    }
  return d;
}

}  // namespace

MeshTopology analyse_topology(const Mesh& mesh) {
  const auto w = weld_by_position(mesh);
  // undirected edge (lo, hi) -> uses in the lo->hi and hi->lo directions
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> uses;
  uses.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    for (size_t e = 0; e < 3; ++e) {
      const uint32_t a = w[mesh.indices[3 * t + e]];
      const uint32_t b = w[mesh.indices[3 * t + (e + 1) % 3]];
      auto& u = uses[edge_key(std::min(a, b), std::max(a, b))];
      (a < b ? u.first : u.second) += 1;
    }
  MeshTopology topo;
  for (const auto& [key, u] : uses) {
    const uint32_t n = u.first + u.second;
    if (n == 1)
      ++topo.boundary_edges;
    else if (n > 2)
      ++topo.nonmanifold_edges;
    else if (u.first != 1)
      ++topo.inconsistent_edges;
  }
  return topo;
}

std::vector<uint32_t> build_adjacency_indices(const Mesh& mesh) {
  const auto w = weld_by_position(mesh);
  const auto d = directed_edges(mesh, w);
  std::vector<uint32_t> out;
  out.reserve(mesh.indices.size() * 2);
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t va = mesh.indices[3 * t + e];
      const uint32_t vb = mesh.indices[3 * t + (e + 1) % 3];
      uint32_t opposite = mesh.indices[3 * t + (e + 2) % 3];
      auto it = d.map.find(edge_key(w[vb], w[va]));  // the neighbour winds the edge the other way
      if (it != d.map.end()) opposite = it->second.second;
      out.push_back(va);
      out.push_back(opposite);
    }
  return out;
}

std::vector<MeshEdge> mesh_edges(const Mesh& mesh) {
  const auto w = weld_by_position(mesh);
  // undirected welded edge -> (triangle, corner) of each use
  std::unordered_map<uint64_t, std::vector<std::pair<uint32_t, uint32_t>>> uses;
  uses.reserve(mesh.indices.size());
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = w[mesh.indices[3 * t + e]];
      const uint32_t b = w[mesh.indices[3 * t + (e + 1) % 3]];
      uses[edge_key(std::min(a, b), std::max(a, b))].emplace_back(t, e);
    }
  const auto endpoints = [&](uint32_t t, uint32_t e) {
    return std::make_pair(mesh.indices[3 * t + e], mesh.indices[3 * t + (e + 1) % 3]);
  };
  std::vector<MeshEdge> out;
  out.reserve(mesh.indices.size() / 2 + 1);
  // In triangle order, so the output does not depend on the hash map's.
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (uint32_t e = 0; e < 3; ++e) {
      const auto [va, vb] = endpoints(t, e);
      const auto& u = uses[edge_key(std::min(w[va], w[vb]), std::max(w[va], w[vb]))];
      if (u.size() == 2) {
        const auto [ot, oe] = u[0].first == t && u[0].second == e ? u[1] : u[0];
        const auto [oa, ob] = endpoints(ot, oe);
        const bool opposite = w[oa] == w[vb] && w[ob] == w[va];
        if (opposite) {
          if (ot < t || (ot == t && oe < e)) continue;  // emitted from the other side
          out.push_back({va, vb, t, int64_t(ot)});
          continue;
        }
      }
      out.push_back({va, vb, t, -1});
    }
  return out;
}

}  // namespace sb
