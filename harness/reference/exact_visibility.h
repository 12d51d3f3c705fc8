#pragma once
// Exact visibility of a rectangular area light or a linear light, without
// sampling (the exact reference's core; docs/results.md). For a point p and
// polygonal casters, and a rectangle:
//   - each candidate triangle is clipped to the pyramid spanned by p and the
//     light rectangle (its four side planes and the light's plane), so only
//     the part between p and the light remains;
//   - that part is projected from p onto the light's plane, where it lies
//     inside the rectangle;
//   - the light's part below p's tangent plane is added as one more polygon
//     (the surface occludes it itself: the one definition of V the Monte
//     Carlo reference and every technique share);
//   - V = 1 − area(union of the polygons) / area(light).
// The union is Clipper's (libpolyclipping, integer coordinates): the light's
// half-size maps to 2^30, so a vertex moves by at most 2^-31 of it and the
// area by under 1e-8 of the light's. The edges neighbouring triangles share
// cancel first; when the outlines left are simple loops apart from each
// other, the union is their area, summed exactly (separate_loops.h).
//
// The occluders are seen from p + ε·n (n made unit), ε = 2^-16 · max(|p|∞,
// M), M the largest |coordinate| of the caster triangles p lies on: the
// Monte Carlo reference's ray offset, by its own test (ray_offset.h); the
// tangent plane stays p's own.
//
// Candidates come from a bounding-volume hierarchy over the casters'
// triangles, culled by the pyramid's five planes; image() culls it once per
// tile of 8×8 pixels, around all of their pyramids (pyramids_bound.h), and
// each pixel then tests only the leaves its tile kept: the same triangles
// that make polygons, so the same V. A closed caster is split
// into its parts, the triangles connected through shared edges (each a
// closed surface, consistently wound: scenes/topology.h), and each part is
// oriented by the sign of its own volume, whatever its mesh's total. A point
// that a part winds around more often than around the light's centre
// (the segment from p to the centre leaves it more often than it enters it)
// is inside it while the light is not: every Monte Carlo shadow ray from it
// is blocked, and the whole light is covered. That happens to a silhouette
// pixel that landed on a back face and took the viewer-facing normal, and
// to a point of one part inside another. Otherwise each part keeps only the
// triangles that face p: a ray that crosses the part crosses one of them
// (were every crossing along the normal, the part would wind around p more
// than around the light), and their projections cover its shadow. This
// holds for any part, wound either way, nested in another (a cavity, a
// room around the light) or touching it, and is fastest when the kept side
// is the near one. A part that the light itself touches, and open and
// double-sided casters, keep every triangle.
// Casters with an alpha mask or an analytic shape have no exact polygonal
// form here: `unsupported()` names the first.
//
// The sun (AreaLight::is_sun(): a disk of directions at infinity): as for a
// rectangle, with the pyramid from p around the sun's cone (no cap: the sun
// is beyond every caster), each clipped triangle projected along its
// directions from p onto the plane at unit distance along the sun's axis,
// and the disk's part below the tangent plane added. The union is Clipper's;
// its part inside the disk is summed in closed form over the union's
// outlines (each edge's triangle with the disk's centre, cut where it
// crosses the circle: straight pieces inside, circular sectors outside), so
// V = 1 − that area / (π tan²(angular_diameter / 2)), the fraction of the
// disk as core::AreaLight defines the sun's V. The inside-a-closed-part test
// follows the axis from p to beyond the casters' bounding sphere.
//
// A linear light (AreaLight::is_segment(), ends A = segment_end(0) and
// B = segment_end(1)): every ray from p to the segment lies in the plane
// through p, A and B, so V is one-dimensional. Each candidate triangle is cut
// by that plane; the cut (a segment) is clipped to the triangle (p, A, B) and
// to the tangent plane, and its ends projected from p onto the line AB give
// the interval of s it hides. The part of the segment below the tangent plane
// is one more interval, and V = 1 − length(union of the intervals). Candidates
// come from the same hierarchy, culled by the wedge's planes through p and
// each end, the plane through A and B that closes it, and the plane through
// p, A and B from both sides. Closed parts keep the side facing p, and the
// inside-a-closed-part test applies, as for a rectangle. A triangle lying in
// that plane hides nothing (as with a rectangle, a set of measure zero in p). When p
// lies on the segment's line (the ends less than 1e-7 rad apart seen from p)
// there is no plane: the rays run along the line, and in each direction a
// triangle crossing it hides everything beyond its nearest crossing. A point
// light has no exact form here (Monte Carlo is exact for it).
//
// The parts: clipping.h (planes, polygons, segments, boxes), light_frame.h,
// caster_bvh.h (the hierarchy), closed_parts.h (parts, their orientation and
// the inside test); a rectangle's V in exact_rectangle.cpp, a segment's in
// exact_segment.cpp, the adaptive reference's proofs in exact_proofs.cpp.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "reference/caster_bvh.h"
#include "reference/light_frame.h"

namespace sb::reference {

// How far from 0 and 1 an exact V must be to be soft: far above Clipper's
// rounding (1e-8 of the light's area), far below one sample's share.
inline constexpr double kPartlyLitMargin = 1e-6;

class ExactVisibility {
 public:
  // `closed`: per mesh of `scene`, whether it is a closed caster (empty: none
  // is, which is correct, only slower).
  ExactVisibility(const core::Scene& scene, const std::vector<bool>& closed = {});
  ~ExactVisibility();
  ExactVisibility(const ExactVisibility&) = delete;
  ExactVisibility& operator=(const ExactVisibility&) = delete;

  // "" when every caster has an exact polygonal form, else why not.
  const std::string& unsupported() const { return unsupported_; }
  // The same, without building anything.
  static std::string unsupported_reason(const core::Scene& scene);

  // V at p, whose surface has the geometric normal n (facing the viewer).
  double visibility(const glm::dvec3& p, const glm::dvec3& n) const;

  // Whether every shadow ray from `origin` (a Monte Carlo ray origin: the
  // surface point `surface` offset along n) to a rectangular light provably
  // reaches it: every light point lies above the plane through `origin`
  // normal to n, and no caster triangle meets the pyramid from `origin` to
  // the light. Then the pixel's V is 1 at every sample count. The pyramid is
  // taken a little wider than the rays (its apex a quarter of the offset
  // back along its axis, the light 1e-5 of its size wider in its own plane,
  // the cap that much beyond it), far beyond float rounding, so a triangle
  // that a ray could graze counts as meeting it. False for a segment or a point light, and
  // when origin is not above the surface. The adaptive reference's proof
  // that a lit pilot missed nothing (adaptive.h).
  bool sees_whole_light(const glm::dvec3& surface, const glm::dvec3& origin,
                        const glm::dvec3& n) const;

  // Whether every shadow ray from `origin` to a rectangular light provably
  // misses it: the whole light below the plane through `origin` normal to
  // n; or origin inside a closed part (as visibility() tells it); or the
  // first closed part that the ray to the light's centre crosses has no
  // silhouette edge seen from origin that meets the pyramid to the light,
  // and does not reach the light's plane inside it. Then the set of rays
  // that cross that part has no boundary inside the pyramid and holds the
  // centre's ray: it is every ray, and the pixel's V is 0 at every sample
  // count. The same wider pyramid as sees_whole_light() (its apex set back
  // only for the silhouette test; which side a triangle faces is seen from
  // origin), an edge-on triangle or an edge shared by other than two
  // triangles counting as silhouette. Needs the closed flags given to the constructor; false
  // where it proves nothing.
  bool hides_whole_light(const glm::dvec3& surface, const glm::dvec3& origin,
                         const glm::dvec3& n) const;

  // One ray origin as the proofs above take it.
  struct ProofPoint {
    glm::dvec3 surface, origin, n;
  };
  // What one walk over a tile of points (a shaft holding every one's
  // pyramid) finds for the proofs at each of them: the triangles that could
  // make one fail. When `whole`, the proof holds at every point at once.
  struct TileCandidates {
    bool usable = false, whole = false;
    uint32_t part = 0;                // hides: the closed part they are of
    std::vector<uint32_t> triangles;  // indices into the casters
  };
  // More, and a tile's walk gives up (then the proofs walk per point).
  static constexpr size_t kMaxCandidates = 512;
  // sees_whole_light()'s candidates for `points`: the caster triangles that
  // may meet the shaft (planes through the edges of a light section holding
  // every pyramid's cap, each supporting all apexes; the cap; a plane below
  // every apex along the first point's normal). Not usable where a point
  // fails the horizon test, or with more than kMaxCandidates.
  void sees_candidates(std::span<const ProofPoint> points, TileCandidates& out) const;
  // hides_whole_light()'s: of the closed part that the first point's ray to
  // the light's centre crosses first (that point outside every part), the
  // triangles in the shaft with a point not in front of the light's plane
  // or an edge inside it between triangles not both facing the points'
  // box the same way. Whole when there is none and no triangle of the part
  // that meets the shaft has its plane through that box: then whether a
  // ray crosses the part never changes between the points' rays, and the
  // first point's does. Whole, with no walk, when every point has all of
  // the light below its horizon.
  void hides_candidates(std::span<const ProofPoint> points, TileCandidates& out) const;
  // The proofs at q, one of the points the candidates were found for
  // (unusable ones: the walks above): the same answers, checking only the
  // candidates.
  bool sees_whole_light(const ProofPoint& q, const TileCandidates& lit) const;
  bool hides_whole_light(const ProofPoint& q, const TileCandidates& dark) const;

  // Whether the light is partly seen from p (geometric normal n): V strictly
  // between kPartlyLitMargin and 1 − kPartlyLitMargin, the penumbra's own
  // definition (reference.h: Result::penumbra). Either proof above settles
  // it where it holds (the usual case for a lit or an umbra point); V itself
  // only where neither does.
  bool partly_lit(const glm::dvec3& p, const glm::dvec3& n) const;

  // The polygons whose union hides a rectangular light from p, in the light's
  // plane (coordinates along half_u and half_v, the light spanning ±half
  // sizes), counter-clockwise: for benchmarks and tests of the union itself.
  std::vector<std::vector<glm::dvec2>> occluding_polygons(const glm::dvec3& p,
                                                          const glm::dvec3& n) const;

  // A segment light's parameter intervals [s0, s1] ⊂ [0, 1] (along
  // AreaLight::segment_end) hidden from p: one per occluding triangle, and
  // the part below the tangent plane; unsorted, overlapping. For benchmarks
  // and tests of the 1-D union. A rectangle's are occluding_polygons().
  std::vector<glm::dvec2> hidden_intervals(const glm::dvec3& p, const glm::dvec3& n) const;

  // The length of the union of `intervals` (each [lo, hi]) within [0, 1];
  // gaps under 1e-9, rounding between abutting triangles, count as covered.
  static double union_length(std::vector<glm::dvec2> intervals);

  // The area of the union of `polygons` (counter-clockwise, inside the light
  // rectangle of the given half sizes), by Clipper.
  static double union_area(const std::vector<std::vector<glm::dvec2>>& polygons, double half_width,
                           double half_height);

  // Polygons in one buffer: polygon i's corners are corners[ends[i - 1]
  // (0 for i = 0), ends[i]). What a pixel's polygons go into, reused, so
  // that a pixel allocates nothing once its thread's buffers have grown.
  struct FlatPolygons {
    std::vector<glm::dvec2> corners;
    std::vector<uint32_t> ends;
    void clear() {
      corners.clear();
      ends.clear();
    }
  };

  // Every covered pixel of a G-buffer (positions.w > 0.5; normals: RGB),
  // in parallel over rows; background pixels get 1.
  core::ImageF image(const core::ImageF& positions, const core::ImageF& normals) const;

  // The polygons whose union hides the sun from p, on the plane at unit
  // distance along its axis (coordinates along the disk's frame, half_u
  // and half_v made unit), inside the square around its disk of radius
  // tan(angular_diameter / 2), counter-clockwise.
  std::vector<std::vector<glm::dvec2>> sun_occluding_polygons(const glm::dvec3& p,
                                                              const glm::dvec3& n) const;

  // The area of `polygon` (counter-clockwise adds, clockwise subtracts)
  // inside the disk of `radius` about the origin, in closed form.
  static double disk_area_inside(const std::vector<glm::dvec2>& polygon, double radius);

  // The area of the union of `polygons` (counter-clockwise, inside the
  // square around the disk) inside the disk of `radius` about the origin:
  // the union by Clipper (the radius maps to 2^30), then its outlines'
  // parts inside the disk in closed form.
  static double union_disk_area(const std::vector<std::vector<glm::dvec2>>& polygons,
                                double radius);

  // The casters' triangles it keeps (a closed caster's, all of them).
  size_t triangle_count() const { return casters_.triangles().size(); }

 private:
  // The offset viewpoint p + eps·n (see above).
  glm::dvec3 viewpoint(const glm::dvec3& surface, const glm::dvec3& n) const;

  // occluding_polygons() into `out`, the occluders seen from `origin`
  // (viewpoint(surface, n)). `leaves`: the hierarchy's leaves and triangles
  // to look in (CasterBvh::leaves, culled by a PyramidsBound around this
  // pyramid),
  // else all of it; the polygons are the same either way.
  void collect_polygons(const glm::dvec3& surface, const glm::dvec3& n, const glm::dvec3& origin,
                        FlatPolygons& out,
                        const std::vector<detail::CasterBvh::Leaf>* leaves = nullptr) const;
  static double union_area(const FlatPolygons& polygons, double half_width, double half_height);

  // A rectangle's V at surface, seen from origin (viewpoint(surface, n));
  // `leaves` as for collect_polygons.
  double rectangle_visibility(const glm::dvec3& surface, const glm::dvec3& n,
                              const glm::dvec3& origin,
                              const std::vector<detail::CasterBvh::Leaf>* leaves = nullptr) const;

  // Whether some of a rectangular light lies above the plane through
  // `surface` normal to n (else V is 0).
  bool light_above(const glm::dvec3& surface, const glm::dvec3& n) const;

  // image() for a rectangular light: tiles of pixels, each culling the
  // hierarchy once for all of its pixels' pyramids (pyramids_bound.h).
  void rectangle_image(const core::ImageF& positions, const core::ImageF& normals,
                       core::ImageF& out) const;

  // The sun's V at p (sun_occluding_polygons, union_disk_area).
  double sun_visibility(const glm::dvec3& p, const glm::dvec3& n) const;

  core::AreaLight light_;
  // Its frame and corners, made once: per pixel they cost 2 % of the time.
  detail::Frame frame_;
  std::array<glm::dvec3, 4> corners_;
  detail::CasterBvh casters_;
  // The casters' bounding sphere: how far the sun's inside test must look.
  glm::dvec3 reach_centre_{0.0};
  double reach_ = 0.0;
  // The largest |coordinate| of the casters' triangles.
  double extent_ = 0.0;
  std::string unsupported_;
};

}  // namespace sb::reference
