#include "occlusion_texture/slicing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.h"

namespace sb::techniques::occlusion_texture {

using core::JobError;
using core::Mesh;
using core::Scene;

Projection projection_from_string(const std::string& s) {
  if (s == "central") return Projection::Central;
  if (s == "orthographic") return Projection::Orthographic;
  throw std::logic_error("unknown occlusion-texture projection '" + s + "'");
}

LookupPlane lookup_plane_from_string(const std::string& s) {
  if (s == "far") return LookupPlane::Far;
  if (s == "mid") return LookupPlane::Mid;
  throw std::logic_error("unknown occlusion-texture lookup plane '" + s + "'");
}

float plane_fraction(LookupPlane plane) { return plane == LookupPlane::Far ? 1.0f : 0.5f; }

SelfSlab self_slab_from_string(const std::string& s) {
  if (s == "skip") return SelfSlab::Skip;
  if (s == "receiver_aware") return SelfSlab::ReceiverAware;
  throw std::logic_error("unknown occlusion-texture self-slab rule '" + s + "'");
}

float point_offset(SelfSlab rule, bool casts_shadow, float caster_offset) {
  return (casts_shadow || rule == SelfSlab::Skip) ? caster_offset : 0.0f;
}

glm::vec2 Slicing::texture_coords(const glm::vec3& local) const {
  return (glm::vec2(local) - origin) * scale / (a * local.z + b) + 0.5f;
}

TextureBox Slicing::kernel(const glm::vec3& p, float plane) const {
  const float z = plane;
  const float r = z / p.z;
  const glm::vec2 centre = glm::vec2(p) * r;
  const glm::vec2 half = glm::vec2(light.half_width, light.half_height) * (1.0f - r);
  const glm::vec2 to_texture = scale / (a * z + b);
  return {(centre - half - origin) * to_texture + 0.5f,
          (centre + half - origin) * to_texture + 0.5f};
}

SlabShare Slicing::share(float z, int k, float offset, LookupPlane plane) const {
  const float near_side = z0 + float(k) * thickness;
  const float top = std::min(near_side + thickness, z - offset * thickness);
  if (!(top > near_side)) return {};
  return {(top - near_side) / thickness, near_side + plane_fraction(plane) * (top - near_side)};
}

Slicing fit_slicing(const Scene& scene, int slabs, Projection projection) {
  Slicing s;
  s.light = LightFrame(scene.light);
  s.slabs = slabs;
  const float scene_scale = std::max(scene.bounds().radius(), 1e-6f);
  constexpr float kMax = std::numeric_limits<float>::max();
  float z_lo = kMax, z_hi = -kMax;
  glm::vec2 lo(kMax), hi(-kMax);
  // The largest D that keeps every caster inside the frustum through the
  // light: |x|·D <= hw·(z + D) for every vertex, per axis.
  float apex = std::numeric_limits<float>::infinity();
  // With no area, the apex is the light's centre and the frustum is fitted
  // to the casters' extent x/z instead.
  glm::vec2 widest_slope(0.0f);
  const glm::vec2 half(s.light.half_width, s.light.half_height);
  for (const Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    for (const uint32_t i : m.indices) {
      const glm::vec3 l = s.light.to_light(m.positions[i]);
      if (!(l.z > 1e-4f * scene_scale))
        throw JobError("caster mesh '" + m.name +
                       "' reaches the light's plane or behind it (a vertex at depth " +
                       std::to_string(l.z) +
                       " along the light's normal): occlusion textures slice the space in front "
                       "of the light only");
      z_lo = std::min(z_lo, l.z);
      z_hi = std::max(z_hi, l.z);
      lo = glm::min(lo, glm::vec2(l));
      hi = glm::max(hi, glm::vec2(l));
      for (int axis = 0; axis < 2; ++axis) {
        const float x = std::fabs(l[axis]);
        if (x > half[axis]) apex = std::min(apex, half[axis] * l.z / (x - half[axis]));
        widest_slope[axis] = std::max(widest_slope[axis], x / l.z);
      }
    }
  }
  if (z_lo == kMax) {
    s.no_casters = true;
    s.thickness = 1.0f;
    return s;
  }
  // Slabs cover the casters' depths with a little room, so that a vertex on
  // the range's ends falls inside the first or the last slab.
  const float room = 1e-3f * std::max(z_hi - z_lo, 1e-3f * scene_scale);
  s.z0 = z_lo - room;
  s.thickness = (z_hi - z_lo + 2.0f * room) / float(slabs);
  constexpr float kMargin = 1.01f;  // casters stay off the texture's border
  if (projection == Projection::Orthographic) {
    s.origin = 0.5f * (lo + hi);
    const float side = std::max(hi.x - lo.x, hi.y - lo.y) * kMargin + 1e-6f * scene_scale;
    s.scale = glm::vec2(1.0f / side);
    s.a = 0.0f;
    s.b = 1.0f;
  } else if (!s.light.has_area()) {
    const float slope = std::max(std::max(widest_slope.x, widest_slope.y), 1e-6f);
    s.scale = glm::vec2(1.0f / (2.0f * slope * kMargin));
    s.a = 1.0f;
    s.b = 0.0f;
  } else if (std::isinf(apex)) {
    s.scale = 1.0f / (2.0f * half * kMargin);
    s.a = 0.0f;
    s.b = 1.0f;
  } else {
    // Fitted to the light, then widened by the margin about its axis.
    s.scale = apex / (2.0f * half * kMargin);
    s.a = 1.0f;
    s.b = apex;
  }
  return s;
}

}  // namespace sb::techniques::occlusion_texture
