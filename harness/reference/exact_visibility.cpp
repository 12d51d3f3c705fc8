#include "reference/exact_visibility.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "reference/closed_parts.h"
#include "reference/light_frame.h"
#include "reference/pyramids_bound.h"
#include "reference/ray_offset.h"

namespace sb::reference {

using core::AnalyticShape;
using core::ImageF;
using core::Mesh;
using core::Scene;

std::string ExactVisibility::unsupported_reason(const Scene& scene) {
  // A segment has an exact form (hidden_intervals); a point's V is 0 or 1.
  if (scene.light.is_point())
    return "the light has no area (the Monte Carlo reference is exact there)";
  if (scene.light.is_sun() && !(scene.light.angular_diameter > 0.0f))
    return "the sun has no size (the Monte Carlo reference is exact there)";
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.casts_shadow) continue;
    if (mesh.alpha_tested())
      return "caster mesh '" + mesh.name +
             "' is alpha-masked: its mask has no exact polygonal form here";
    if (mesh.analytic.kind != AnalyticShape::Kind::None)
      return "caster mesh '" + mesh.name +
             "' occludes as an analytic shape, which has no polygonal form";
  }
  return "";
}

ExactVisibility::ExactVisibility(const Scene& scene, const std::vector<bool>& closed)
    : light_(scene.light),
      frame_(light_),
      corners_(frame_.corners()),
      unsupported_(unsupported_reason(scene)) {
  std::vector<detail::CasterTriangle> triangles;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!mesh.casts_shadow) continue;
    const bool is_closed = m < closed.size() && closed[m] && !mesh.double_sided;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      detail::CasterTriangle t{glm::dvec3(mesh.positions[mesh.indices[i]]),
                               glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                               glm::dvec3(mesh.positions[mesh.indices[i + 2]])};
      t.mesh = uint32_t(m);
      t.normal = glm::cross(t.b - t.a, t.c - t.a);
      t.outward = is_closed ? 1 : 0;  // closed; find_parts() orients it
      triangles.push_back(t);
    }
  }
  core::Bounds bounds;
  for (const auto& t : triangles)
    for (const glm::dvec3& x : {t.a, t.b, t.c}) {
      bounds.extend(glm::vec3(x));
      extent_ = std::max({extent_, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
    }
  if (!bounds.empty()) {
    reach_centre_ = glm::dvec3(bounds.center());
    reach_ = double(bounds.radius()) * (1.0 + 1e-6) + 1e-6;
  }
  casters_ = detail::CasterBvh(std::move(triangles));
  // After the hierarchy has put the triangles in their final order.
  detail::link_neighbours(casters_.triangles());
  detail::find_parts(casters_.triangles(), light_);
}

ExactVisibility::~ExactVisibility() = default;

glm::dvec3 ExactVisibility::viewpoint(const glm::dvec3& surface, const glm::dvec3& n) const {
  // The caster triangles the surface point lies on, by the Monte Carlo
  // reference's own test (ray_offset.h).
  const double radius = detail::offset_radius(surface);
  double largest = 0.0;
  casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        const glm::dvec3 outside = glm::max(lo - surface, glm::max(surface - hi, glm::dvec3(0.0)));
        return glm::dot(outside, outside) <= radius * radius;
      },
      [&](const detail::CasterTriangle& t) {
        largest = std::max(largest, detail::lies_on_scale(surface, radius, t.a, t.b, t.c));
      });
  // Along the unit normal, as the Monte Carlo rays start.
  const double length = glm::length(n);
  return length > 0.0 ? surface + detail::offset_from(surface, largest) / length * n : surface;
}

double ExactVisibility::visibility(const glm::dvec3& p, const glm::dvec3& n) const {
  if (light_.is_sun()) return sun_visibility(p, n);
  if (light_.is_segment()) return std::clamp(1.0 - union_length(hidden_intervals(p, n)), 0.0, 1.0);
  return rectangle_visibility(p, n, viewpoint(p, n));
}

bool ExactVisibility::light_above(const glm::dvec3& surface, const glm::dvec3& n) const {
  return !std::all_of(corners_.begin(), corners_.end(),
                      [&](const glm::dvec3& c) { return glm::dot(n, c - surface) <= 0.0; });
}

double ExactVisibility::rectangle_visibility(
    const glm::dvec3& surface, const glm::dvec3& n, const glm::dvec3& origin,
    const std::vector<detail::CasterBvh::Leaf>* leaves) const {
  // All of the light on or below the tangent plane: the horizon polygon is
  // the light, and the union would be too.
  if (!light_above(surface, n)) return 0.0;
  const detail::Frame& f = frame_;
  thread_local FlatPolygons polygons;
  collect_polygons(surface, n, origin, polygons, leaves);
  if (polygons.ends.empty()) return 1.0;
  return std::clamp(1.0 - union_area(polygons, f.hw, f.hh) / (4.0 * f.hw * f.hh), 0.0, 1.0);
}

bool ExactVisibility::partly_lit(const glm::dvec3& p, const glm::dvec3& n) const {
  if (!light_.is_segment() && !light_.is_point() && !light_.is_sun()) {
    const glm::dvec3 origin = viewpoint(p, n);
    if (sees_whole_light(p, origin, n) || hides_whole_light(p, origin, n)) return false;
    const double v = rectangle_visibility(p, n, origin);
    return v > kPartlyLitMargin && v < 1.0 - kPartlyLitMargin;
  }
  const double v = visibility(p, n);
  return v > kPartlyLitMargin && v < 1.0 - kPartlyLitMargin;
}

ImageF ExactVisibility::image(const ImageF& positions, const ImageF& normals) const {
  ImageF out(positions.width, positions.height, 1, 1.0f);
  if (!light_.is_sun() && !light_.is_segment()) {
    rectangle_image(positions, normals, out);
    return out;
  }
  tbb::parallel_for(0, positions.height, [&](int y) {
    for (int x = 0; x < positions.width; ++x) {
      const size_t i = size_t(y) * size_t(positions.width) + size_t(x);
      const float* pos = &positions.data[i * 4];
      if (!(pos[3] > 0.5f)) continue;
      const float* nor = &normals.data[i * size_t(normals.channels)];
      out.data[i] =
          float(visibility(glm::dvec3(pos[0], pos[1], pos[2]), glm::dvec3(nor[0], nor[1], nor[2])));
    }
  });
  return out;
}

void ExactVisibility::rectangle_image(const ImageF& positions, const ImageF& normals,
                                      ImageF& out) const {
  // Neighbouring pixels' pyramids mostly overlap: a tile's pixels share one
  // walk of the hierarchy, bounded around all of their pyramids, and each
  // then tests only the leaves it kept (the same polygons as its own walk).
  constexpr int kTile = 8;
  const int columns = (positions.width + kTile - 1) / kTile;
  const int rows = (positions.height + kTile - 1) / kTile;
  const detail::Frame& f = frame_;
  tbb::parallel_for(0, columns * rows, [&](int tile) {
    struct Pixel {
      size_t i;
      glm::dvec3 surface, n;
    };
    std::array<Pixel, size_t(kTile * kTile)> pixels;
    std::array<glm::dvec3, size_t(kTile * kTile)> origins;
    size_t count = 0;
    const int x0 = (tile % columns) * kTile, y0 = (tile / columns) * kTile;
    for (int y = y0; y < std::min(y0 + kTile, positions.height); ++y)
      for (int x = x0; x < std::min(x0 + kTile, positions.width); ++x) {
        const size_t i = size_t(y) * size_t(positions.width) + size_t(x);
        const float* pos = &positions.data[i * 4];
        if (!(pos[3] > 0.5f)) continue;
        const float* nor = &normals.data[i * size_t(normals.channels)];
        const glm::dvec3 surface(pos[0], pos[1], pos[2]), n(nor[0], nor[1], nor[2]);
        if (!light_above(surface, n)) {
          out.data[i] = 0.0f;
          continue;
        }
        pixels[count] = {i, surface, n};
        origins[count++] = viewpoint(surface, n);
      }
    if (count == 0) return;
    thread_local std::vector<detail::CasterBvh::Leaf> leaves;
    leaves.clear();
    const detail::PyramidsBound bound(f, origins.data(), count, extent_);
    casters_.leaves(
        [&](const glm::dvec3& lo, const glm::dvec3& hi) { return bound.may_meet(lo, hi); },
        [&](const detail::CasterTriangle& t) { return bound.may_meet(t.a, t.b, t.c); }, leaves);
    for (size_t k = 0; k < count; ++k)
      out.data[pixels[k].i] =
          float(rectangle_visibility(pixels[k].surface, pixels[k].n, origins[k], &leaves));
  });
}

}  // namespace sb::reference
