#include "shadow_volume/silhouette.h"

#include <algorithm>
#include <array>
#include <bit>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "shadow_volume/pn_triangle.h"

namespace sb::techniques::shadow_volume {

using core::Mesh;
using plugin::MeshEdge;

SilhouetteMode silhouette_mode_from_string(const std::string& s) {
  if (s == "discrete") return SilhouetteMode::Discrete;
  if (s == "accurate") return SilhouetteMode::Accurate;
  if (s == "smooth") return SilhouetteMode::Smooth;
  throw std::invalid_argument("unknown silhouette mode '" + s + "'");
}

SilhouetteMesh make_silhouette_mesh(const Mesh& mesh, const std::vector<MeshEdge>& edges) {
  SilhouetteMesh out;
  const size_t triangles = mesh.triangle_count();
  const bool has_normals = mesh.normals.size() == mesh.positions.size();
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  // Mesh vertex index → corner, per triangle, to find where an edge starts.
  for (size_t t = 0; t < triangles; ++t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
    const glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
    const glm::vec3 cross = glm::cross(b - a, c - a);
    const float len = glm::length(cross);
    const glm::vec3 face = len > 0.0f ? cross / len : glm::vec3(0.0f);
    out.face_normals.push_back(face);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + size_t(k)];
      const glm::vec3 p = mesh.positions[v];
      out.positions.push_back(p);
      glm::vec3 n = has_normals ? mesh.normals[v] : face;
      const float nl = glm::length(n);
      out.normals.push_back(nl > 0.0f ? n / nl : face);
      const auto [it, fresh] = ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size()));
      out.welded.push_back(it->second);
    }
  }
  out.edge_of_corner.assign(3 * triangles, SilhouetteMesh::kNone);
  // The corner of triangle t whose position is welded with mesh vertex v.
  const auto corner_at = [&](size_t t, uint32_t v) {
    const glm::vec3 p = mesh.positions[v];
    for (uint32_t k = 0; k < 3; ++k)
      if (out.positions[3 * t + k] == p) return uint32_t(3 * t + k);
    throw std::logic_error("an edge's vertex is not a corner of its triangle");
  };
  for (const MeshEdge& e : edges) {
    SilhouetteMesh::Edge edge;
    edge.left_corner = corner_at(e.left, e.v0);
    out.edge_of_corner[edge.left_corner] = uint32_t(out.edges.size());
    if (e.right >= 0) {
      edge.right_corner = corner_at(size_t(e.right), e.v1);
      out.edge_of_corner[edge.right_corner] = uint32_t(out.edges.size());
    }
    out.edges.push_back(edge);
  }
  for (uint32_t c : out.edge_of_corner)
    if (c == SilhouetteMesh::kNone) throw std::logic_error("a triangle edge is in no edge list");
  return out;
}

namespace {

uint32_t next_corner(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }

constexpr uint64_t kVertexKey = uint64_t(1) << 63;

// The lit part of an edge, in its own parameter x ∈ [0, 1] from v0 to v1.
struct Interval {
  float lo = 0.0f, hi = 0.0f;
  bool empty() const { return !(lo < hi); }
};

// What one triangle says about one of its edges: f at the edge's v0 and v1.
struct EdgeSide {
  uint32_t triangle = 0;
  bool v0_is_start = true;  // the triangle winds v0 → v1 (the edge's left)
  float f0 = 0.0f, f1 = 0.0f;
  bool lit0() const { return f0 > 0.0f; }
  bool lit1() const { return f1 > 0.0f; }
  // The crossing, when lit0() != lit1(): never a division by zero (see the header).
  float crossing() const { return f0 / (f0 - f1); }
  Interval lit() const {
    if (lit0() && lit1()) return {0.0f, 1.0f};
    if (lit0()) return {0.0f, crossing()};
    if (lit1()) return {crossing(), 1.0f};
    return {};
  }
};

using detail::Segment;

class Extractor {
 public:
  Extractor(const SilhouetteMesh& m, const glm::vec3& light, const SilhouetteSettings& s,
            Silhouette& out)
      : m_(m),
        light_(light),
        s_(s),
        out_(out),
        f_(out.scratch.f),
        segments_(out.scratch.segments),
        inner_(out.scratch.inner),
        fan_(out.scratch.fan),
        order_(out.scratch.order),
        used_(out.scratch.used) {}

  void run() {
    for (auto& loop : out_.loops) loop.clear();  // kept, with their storage
    loops_used_ = 0;
    out_.cap.clear();
    out_.open_loops = 0;
    segments_.clear();
    inner_.clear();
    f_.resize(m_.positions.size());
    for (size_t c = 0; c < m_.positions.size(); ++c) {
      const glm::vec3 n =
          s_.mode == SilhouetteMode::Discrete ? m_.face_normals[c / 3] : m_.normals[c];
      // Discrete: the face's plane through its first corner, as the shader tests it.
      const glm::vec3 p =
          s_.mode == SilhouetteMode::Discrete ? m_.positions[c - c % 3] : m_.positions[c];
      f_[c] = glm::dot(n, light_ - p);
    }
    for (uint32_t t = 0; 3 * t < m_.positions.size(); ++t) triangle(t);
    for (uint32_t e = 0; e < m_.edges.size(); ++e) edge(e);
    chain();
    out_.loops.resize(loops_used_);
  }

 private:
  EdgeSide side(uint32_t e, bool left) const {
    const auto& edge = m_.edges[e];
    const uint32_t c = left ? edge.left_corner : edge.right_corner;
    // The left triangle starts at v0, the right at v1.
    return left ? EdgeSide{c / 3, true, f_[c], f_[next_corner(c)]}
                : EdgeSide{c / 3, false, f_[next_corner(c)], f_[c]};
  }
  glm::vec3 edge_point(uint32_t e, float x) const {
    const uint32_t c = m_.edges[e].left_corner;
    return (1.0f - x) * m_.positions[c] + x * m_.positions[next_corner(c)];
  }
  uint64_t key(uint32_t e, float x) const {
    const uint32_t c = m_.edges[e].left_corner;
    if (x <= 0.0f) return kVertexKey | m_.welded[c];
    if (x >= 1.0f) return kVertexKey | m_.welded[next_corner(c)];
    return (uint64_t(e) << 32) | std::bit_cast<uint32_t>(x);
  }
  // Barycentric coordinates in triangle `side.triangle` of the edge's point x.
  glm::vec3 barycentric(uint32_t e, const EdgeSide& side, float x) const {
    const auto& edge = m_.edges[e];
    const uint32_t c = side.v0_is_start ? edge.left_corner : edge.right_corner;
    // Corner c holds v0 (left) or v1 (right); its successor holds the other.
    const float wc = side.v0_is_start ? 1.0f - x : x;
    glm::vec3 b(0.0f);
    b[int(c % 3)] = wc;
    b[int(next_corner(c) % 3)] = 1.0f - wc;
    return b;
  }
  PnTriangle patch(uint32_t t) const {
    return PnTriangle({m_.positions[3 * t], m_.positions[3 * t + 1], m_.positions[3 * t + 2]},
                      {m_.normals[3 * t], m_.normals[3 * t + 1], m_.normals[3 * t + 2]});
  }
  glm::vec3 smooth_point(const PnTriangle& pn, const glm::vec3& b) const {
    return pn.point(b) - s_.offset * pn.normal(b);
  }
  bool smooth() const { return s_.mode == SilhouetteMode::Smooth; }
  SilhouetteVertex vertex(uint32_t e, const EdgeSide& side, float x, const PnTriangle* pn) const {
    const glm::vec3 p = edge_point(e, x);
    return {p, pn ? smooth_point(*pn, barycentric(e, side, x)) : p};
  }

  // A partly lit triangle: its lit polygon into the cap, the line f = 0 across
  // it into the boundary (subdivided in smooth mode).
  void triangle(uint32_t t) {
    std::array<bool, 3> lit{};
    int lit_count = 0;
    for (uint32_t k = 0; k < 3; ++k) lit[k] = f_[3 * t + k] > 0.0f, lit_count += lit[k] ? 1 : 0;
    if (lit_count == 0) return;
    const glm::vec3* p = &m_.positions[3 * t];
    const std::optional<PnTriangle> pn =
        smooth() && lit_count < 3 ? std::optional(patch(t)) : std::nullopt;
    Segment seg;
    std::array<glm::vec3, 9> poly{};
    size_t n = 0, out_at = 0;
    bool breakpoints = false;
    // Where the triangle across edge k crosses it, if inside this side's lit
    // part: a vertex of the lit polygon too, else the two caps would meet in
    // a T-junction, which rasterises with cracks.
    const auto twin_breakpoint = [&](uint32_t k, float from, float to) {
      const uint32_t c = 3 * t + k;
      const uint32_t e = m_.edge_of_corner[c];
      const bool left = m_.edges[e].left_corner == c;
      if (m_.edges[e].right_corner == SilhouetteMesh::kNone) return;
      const EdgeSide twin = side(e, !left);
      if (twin.lit0() == twin.lit1()) return;
      const float x = twin.crossing();
      const float walked = left ? x : 1.0f - x;  // 0 at corner k, 1 at corner k + 1
      if (!(walked > from && walked < to)) return;
      poly[n++] = edge_point(e, x);
      breakpoints = true;
    };
    // The walking parameter of this triangle's own crossing on edge k.
    const auto own_walked = [&](uint32_t k) {
      const uint32_t c = 3 * t + k;
      const uint32_t e = m_.edge_of_corner[c];
      const bool left = m_.edges[e].left_corner == c;
      const float x = side(e, left).crossing();
      return left ? x : 1.0f - x;
    };
    const auto crossing = [&](uint32_t k) {
      const uint32_t c = 3 * t + k;
      const uint32_t e = m_.edge_of_corner[c];
      const EdgeSide s = side(e, m_.edges[e].left_corner == c);
      const float x = s.crossing();
      poly[n++] = edge_point(e, x);
      return std::tuple{key(e, x), vertex(e, s, x, pn ? &*pn : nullptr), barycentric(e, s, x)};
    };
    // Start at a lit corner after an unlit one (any corner when all are lit).
    uint32_t first = 0;
    if (lit_count < 3)
      while (!lit[first] || lit[(first + 2) % 3]) first = (first + 1) % 3;
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t k = (first + i) % 3, next = (k + 1) % 3;
      if (lit[k]) poly[n++] = p[k];
      if (lit[k] && lit[next]) {
        twin_breakpoint(k, 0.0f, 1.0f);
      } else if (lit[k]) {  // leaving the lit region: the boundary starts here
        twin_breakpoint(k, 0.0f, own_walked(k));
        std::tie(seg.from, seg.a, seg_b_out_) = crossing(k);
        out_at = n;
      } else if (lit[next]) {
        std::tie(seg.to, seg.b, seg_b_in_) = crossing(k);
        twin_breakpoint(k, own_walked(k), 1.0f);
      }
    }
    if (lit_count < 3) {
      seg.inner_first = uint32_t(inner_.size());
      if (pn) subdivide(*pn, t, 0.0f, 1.0f, seg.a.smooth, seg.b.smooth, 0);
      seg.inner_count = uint32_t(inner_.size()) - seg.inner_first;
      segments_.push_back(seg);
    } else {
      out_at = n;
    }
    // The lit polygon, with the subdivision points on its clip edge so that
    // the cap and the strip share every vertex.
    std::vector<glm::vec3>& fan = fan_;
    fan.assign(poly.begin(), poly.begin() + long(out_at));
    for (uint32_t i = 0; i < seg.inner_count; ++i) fan.push_back(inner_[seg.inner_first + i].mesh);
    fan.insert(fan.end(), poly.begin() + long(out_at), poly.begin() + long(n));
    if (!breakpoints) {
      // From the first corner, which is on neither end of the clip line.
      for (size_t i = 1; i + 1 < fan.size(); ++i)
        out_.cap.insert(out_.cap.end(), {fan[0], fan[i], fan[i + 1]});
      return;
    }
    // A breakpoint lies on an edge next to any corner: fan from the centroid
    // instead, so that no triangle is a sliver along an edge.
    glm::vec3 centroid(0.0f);
    for (const glm::vec3& q : fan) centroid += q;
    centroid /= float(fan.size());
    for (size_t i = 0; i < fan.size(); ++i)
      out_.cap.insert(out_.cap.end(), {centroid, fan[i], fan[(i + 1) % fan.size()]});
  }

  // Points of the clip line between s0 and s1 (0 at the exit, 1 at the
  // entry), in order, until the curve is within epsilon of its chords.
  void subdivide(const PnTriangle& pn, uint32_t t, float s0, float s1, const glm::vec3& p0,
                 const glm::vec3& p1, int depth) {
    if (depth >= s_.max_depth) return;
    const float sm = 0.5f * (s0 + s1);
    const glm::vec3 b = (1.0f - sm) * seg_b_out_ + sm * seg_b_in_;
    const glm::vec3 pm = smooth_point(pn, b);
    if (glm::length(0.5f * (p0 + p1) - pm) < s_.epsilon) return;
    subdivide(pn, t, s0, sm, p0, pm, depth + 1);
    const glm::vec3* q = &m_.positions[3 * t];
    inner_.push_back({b.x * q[0] + b.y * q[1] + b.z * q[2], pm});
    subdivide(pn, t, sm, s1, pm, p1, depth + 1);
  }

  // The parts of an edge lit on one side only: boundary pieces along it.
  void edge(uint32_t e) {
    const bool two_sided = m_.edges[e].right_corner != SilhouetteMesh::kNone;
    const EdgeSide l = side(e, true);
    if (!two_sided) {
      along(e, l, l.lit(), {});
      return;
    }
    const EdgeSide r = side(e, false);
    along(e, l, l.lit(), r.lit());
    along(e, r, r.lit(), l.lit());
  }
  void along(uint32_t e, const EdgeSide& s, Interval mine, Interval other) {
    if (mine.empty()) return;
    std::array<Interval, 2> parts{mine, {}};
    if (!other.empty())
      parts = {Interval{mine.lo, std::min(mine.hi, other.lo)},
               Interval{std::max(mine.lo, other.hi), mine.hi}};
    std::optional<PnTriangle> pn;
    for (const Interval& part : parts) {
      if (part.empty()) continue;
      if (smooth() && !pn) pn = patch(s.triangle);
      // Wound as the side's triangle winds the edge.
      const float x0 = s.v0_is_start ? part.lo : part.hi;
      const float x1 = s.v0_is_start ? part.hi : part.lo;
      const PnTriangle* patch_ptr = pn ? &*pn : nullptr;
      segments_.push_back(Segment{key(e, x0), key(e, x1), vertex(e, s, x0, patch_ptr),
                                  vertex(e, s, x1, patch_ptr), uint32_t(inner_.size()), 0});
    }
  }

  // Joins the segments end to start into loops.
  void chain() {
    order_.clear();
    for (uint32_t i = 0; i < segments_.size(); ++i) order_.emplace_back(segments_[i].from, i);
    std::sort(order_.begin(), order_.end());
    used_.assign(segments_.size(), 0);
    const auto next_from = [&](uint64_t k) -> int64_t {
      auto it = std::lower_bound(order_.begin(), order_.end(), std::make_pair(k, uint32_t(0)));
      for (; it != order_.end() && it->first == k; ++it)
        if (!used_[it->second]) return it->second;
      return -1;
    };
    for (uint32_t start = 0; start < segments_.size(); ++start) {
      if (used_[start]) continue;
      if (loops_used_ == out_.loops.size()) out_.loops.emplace_back();
      std::vector<SilhouetteVertex>& loop = out_.loops[loops_used_++];
      int64_t cur = start;
      bool closed = false;
      while (true) {
        const Segment& s = segments_[size_t(cur)];
        used_[size_t(cur)] = 1;
        loop.push_back(s.a);
        loop.insert(loop.end(), inner_.begin() + s.inner_first,
                    inner_.begin() + s.inner_first + s.inner_count);
        const bool back_at_start = s.to == segments_[start].from;
        const int64_t next = back_at_start ? -1 : next_from(s.to);
        if (!back_at_start && next < 0) {  // a dead end: only on a mesh that is not closed
          loop.push_back(s.b);
          break;
        }
        const SilhouetteVertex& following =
            back_at_start ? segments_[start].a : segments_[size_t(next)].a;
        // A crease: the two sides' smooth points differ; keep both.
        if (s.b.smooth != following.smooth) loop.push_back(s.b);
        if (back_at_start) {
          closed = true;
          break;
        }
        cur = next;
      }
      if (!closed) ++out_.open_loops;
    }
  }

  const SilhouetteMesh& m_;
  glm::vec3 light_;
  const SilhouetteSettings& s_;
  Silhouette& out_;
  std::vector<float>& f_;
  std::vector<Segment>& segments_;
  std::vector<SilhouetteVertex>& inner_;
  std::vector<glm::vec3>& fan_;
  std::vector<std::pair<uint64_t, uint32_t>>& order_;
  std::vector<char>& used_;
  size_t loops_used_ = 0;
  glm::vec3 seg_b_out_{0.0f}, seg_b_in_{0.0f};
};

}  // namespace

void extract_silhouette(const SilhouetteMesh& mesh, const glm::vec3& light,
                        const SilhouetteSettings& settings, Silhouette& out) {
  Extractor(mesh, light, settings, out).run();
}

}  // namespace sb::techniques::shadow_volume
