#pragma once
// Percentage-closer soft shadows' estimate (Fernando 2005), as GLSL a
// lit_fraction() may call: a blocker search, then the penumbra's width,
// from similar triangles between a square light of side L centred on the
// map's eye and a blocker plane:
//   search WIDTH on the near plane   L·(z_r − n)/z_r
//   penumbra WIDTH on the receiver   w = L·(z_r − z_b)/z_b
// with n the map's near plane and z_r, z_b the receiver's and the mean
// blocker's distances along the light's axis (view depth, world units). Both
// are converted to map uv: the map spans 2·d·tan_half_fov world units at
// distance d. They are full WIDTHS; a PCF kernel over the penumbra takes
// half of one as its RADIUS (common/glsl_pcf.h), as pcss does:
//   pcf_grid_radius(t, h, 0.5 · penumbra_width_uv(...)).
// Under the sun (an orthographic map, LightFrustum::orthographic) the light
// is a cone of angular diameter α from every receiver; with
// spread = 2·tan(α/2) and S the map's side in world units:
//   search WIDTH (map)        spread·(z_r − n)/S uv   sun_search_width_uv()
//   penumbra WIDTH (receiver) spread·(z_r − z_b)/S uv sun_penumbra_width_uv()
// Pass kPcssGlsl (and kPcfGlsl for the filter) as the lookup's kit GLSL
// (common/map_lookup.h), as pcss does.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the map lookup's prelude (depth_map, view_depth, receiver_gradient);
//   out    blocker searches return (mean blocker view depth, blocker count),
//          (0, 0) when no tap is a blocker; widths are >= 0 in map uv;
//   GL     none of its own: the searches read depth_map (unit 3) only;
//   cost   one depth_map fetch per search tap; widths are arithmetic.

namespace sb::techniques {

// PCSS's blocker search over a grid or a disk, and its search and penumbra widths.
// units: widths and radii in map uv; depths in view depth (world units).
// cost: one depth_map fetch per search tap.
inline constexpr const char* kPcssGlsl = R"glsl(
#ifndef MAX_DISK_TAPS
#define MAX_DISK_TAPS 64
#endif

// The blocker search's full WIDTH on the near plane, L·(z_r − n)/z_r, in map uv.
// The part of the map through which the receiver sees the whole light.
// units: light_size (L) and receiver_depth (z_r), near_plane (n) view depth; returns uv.
// cost: arithmetic only.
float pcss_search_width_uv(float light_size, float receiver_depth, float near_plane,
                           float tan_half_fov) {
  return light_size * (receiver_depth - near_plane) /
         (receiver_depth * 2.0 * near_plane * tan_half_fov);
}

// The penumbra's full WIDTH at the receiver, w = L·(z_r − z_b)/z_b, in map uv at depth z_r.
// 0 when the blockers are not in front of the receiver. A PCF's RADIUS is half of it.
// units: light_size (L) world; receiver_depth (z_r), blocker_depth (z_b) view depth; returns uv.
// cost: arithmetic only.
float penumbra_width_uv(float light_size, float receiver_depth, float blocker_depth,
                        float tan_half_fov) {
  return light_size * max(receiver_depth - blocker_depth, 0.0) /
         (blocker_depth * 2.0 * receiver_depth * tan_half_fov);
}

// The blocker search's full WIDTH under the sun, spread·(z_r − n)/S in map
// uv: the part of the map through which the receiver sees the sun's cone.
// units: spread (2·tan(α/2)) per unit depth; receiver_depth, near_plane
// view depth and map_side (S) world units; returns uv.
// cost: arithmetic only.
float sun_search_width_uv(float spread, float receiver_depth, float near_plane, float map_side) {
  return spread * max(receiver_depth - near_plane, 0.0) / map_side;
}

// The penumbra's full WIDTH at the receiver under the sun,
// spread·(z_r − z_b)/S in map uv; 0 when the blockers are not in front of
// the receiver.
// units: spread (2·tan(α/2)) per unit depth; receiver_depth, blocker_depth
// view depth and map_side (S) world units; returns uv.
// cost: arithmetic only.
float sun_penumbra_width_uv(float spread, float receiver_depth, float blocker_depth,
                            float map_side) {
  return spread * max(receiver_depth - blocker_depth, 0.0) / map_side;
}

// Mean view depth and count of blockers among (2·half_side+1)² grid taps spanning width_uv.
// A tap is a blocker when its map depth is nearer than the receiver's plane at that tap
// (t.z plus receiver_gradient, zero unless receiver_plane_bias is on).
// units: width_uv a full WIDTH in map uv (taps half of it from t); returns (view depth, count).
// cost: (2·half_side+1)² depth_map fetches.
vec2 blocker_search_grid(vec3 t, int half_side, float width_uv) {
  vec2 step = vec2(0.5 * width_uv / float(max(half_side, 1)));
  float blockers = 0.0, depth_sum = 0.0;
  for (int y = -half_side; y <= half_side; ++y)
    for (int x = -half_side; x <= half_side; ++x) {
      vec2 o = vec2(x, y) * step;
      float w = texture(depth_map, t.xy + o).r;
      if (w < t.z + dot(receiver_gradient, o)) {
        depth_sum += view_depth(w);
        blockers += 1.0;
      }
    }
  return vec2(blockers > 0.0 ? depth_sum / blockers : 0.0, blockers);
}

// Mean view depth and count of blockers among the first `count` taps of a rotated disk.
// Tap i lies at t + rotation · disk[i] · radius_uv (a RADIUS: half the search width).
// units: disk on the unit disk (sample_disks.h); radius_uv in map uv; returns (view depth, count).
// cost: count depth_map fetches.
vec2 blocker_search_disk(vec3 t, vec2 disk[MAX_DISK_TAPS], int count, mat2 rotation,
                         vec2 radius_uv) {
  float blockers = 0.0, depth_sum = 0.0;
  for (int i = 0; i < count; ++i) {
    vec2 o = rotation * disk[i] * radius_uv;
    float w = texture(depth_map, t.xy + o).r;
    if (w < t.z + dot(receiver_gradient, o)) {
      depth_sum += view_depth(w);
      blockers += 1.0;
    }
  }
  return vec2(blockers > 0.0 ? depth_sum / blockers : 0.0, blockers);
}
)glsl";

}  // namespace sb::techniques
