// jeep — the scene Atty et al. 2006 and Eisemann & Décoret 2008 use to show
// how shadow cost scales with geometry: `count` procedural jeeps (body, bonnet,
// grille, fenders, windscreen frame, roll bar, seats, steering wheel, bumpers,
// headlights, four wheels and a spare, each part its own closed caster mesh)
// on a ground plane under a square area light.
//
// | parameter    | default | meaning                                                  |
// |--------------|---------|----------------------------------------------------------|
// | count        | 1       | number of jeeps (1..1024)                                |
// | layout       | "grid"  | grid: ceil(sqrt(count)) per row; rows: 8 side by side    |
// | spacing      | 1.0     | smallest gap between neighbours' bounding boxes (metres) |
// | tessellation | 20      | segments of round parts; tubes and tyre sections get half |
// | light_size   | 2.0     | side of the square area light (metres)                   |
// | seed         | 1       | per-jeep yaw (±8°) and offset (±0.2·spacing); 0: aligned |
//
// A jeep is about 3.4 m long, 1.6 m wide and 1.7 m tall (roll bar) and has
// 3620 triangles at the default tessellation. Light and camera are derived
// from the set's extent: the light sits above and to the front-right at
// max(18, 3·radius) from the set's centre, the camera looks down at 40° from
// the front-left and is fitted so that every jeep and its shadow fill a 4:3
// frame; the ground reaches the far plane in every corner of the view.
#include "scenes/jeep.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/counter_rng.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"
#include "scenes/triangle_budget.h"

namespace sb {

using core::Bounds;
using core::choice_param;
using core::float_param;
using core::int_param;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

const glm::vec3 kOlive(0.30f, 0.33f, 0.16f);
const glm::vec3 kDarkOlive(0.20f, 0.22f, 0.11f);
const glm::vec3 kTyre(0.07f, 0.07f, 0.07f);
const glm::vec3 kRim(0.55f, 0.56f, 0.54f);
const glm::vec3 kSteel(0.12f, 0.12f, 0.12f);
const glm::vec3 kSeat(0.16f, 0.13f, 0.10f);
const glm::vec3 kLamp(0.92f, 0.90f, 0.78f);

constexpr float kTyreMajor = 0.255f;
constexpr float kTyreMinor = 0.125f;
constexpr float kWheelRadius = kTyreMajor + kTyreMinor;
// A hair above the ground so rounding never puts a tyre vertex below y = 0.
constexpr float kAxleHeight = kWheelRadius + 0.005f;

glm::mat3 rotation_x(float degrees) {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(1, 0, 0)));
}

Mesh part(const std::string& prefix, const std::string& name, glm::vec3 albedo, Mesh m) {
  m.name = prefix + "/" + name;
  m.albedo = albedo;
  m.casts_shadow = true;
  return m;
}

// Tyre and rim of a wheel whose outward axis is `out` (from the vehicle).
void add_wheel(std::vector<Mesh>& parts, const std::string& prefix, const std::string& tag,
               glm::vec3 center, glm::vec3 out, int segs, int half_segs) {
  parts.push_back(part(prefix, "tyre_" + tag, kTyre,
                       make_torus("", center, out, kTyreMajor, kTyreMinor, segs, half_segs)));
  // The rim fills the torus' hole and is recessed from the tyre's outer wall;
  // the hub sticks out of the rim.
  Mesh rim = make_cylinder("", center - 0.10f * out, out, 0.20f, 0.20f, 0.18f, segs);
  append_mesh(rim, make_cylinder("", center + 0.07f * out, out, 0.06f, 0.05f, 0.045f, half_segs));
  parts.push_back(part(prefix, "rim_" + tag, kRim, std::move(rim)));
}

}  // namespace

std::vector<Mesh> make_jeep(const std::string& prefix, int tessellation) {
  const int segs = tessellation;
  const int half_segs = std::max(4, tessellation / 2);
  const int quarter_segs = std::max(3, tessellation / 4);
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  std::vector<Mesh> parts;

  // Wheels: track 1.32 m, wheelbase 2.0 m; +x is the jeep's left.
  const float track = 0.66f, axle = 1.0f;
  add_wheel(parts, prefix, "fl", {track, kAxleHeight, axle}, x, segs, half_segs);
  add_wheel(parts, prefix, "fr", {-track, kAxleHeight, axle}, -x, segs, half_segs);
  add_wheel(parts, prefix, "rl", {track, kAxleHeight, -axle}, x, segs, half_segs);
  add_wheel(parts, prefix, "rr", {-track, kAxleHeight, -axle}, -x, segs, half_segs);
  // The spare hangs on the rear wall, off-centre to the right as on a Willys.
  add_wheel(parts, prefix, "spare", {-0.35f, 0.85f, -1.58f}, -z, segs, half_segs);
  append_mesh(parts.back(), make_box("", {-0.35f, 0.85f, -1.46f}, {0.06f, 0.06f, 0.05f}));

  // Ladder frame rails and axles, mostly hidden, but they shadow the ground.
  Mesh chassis = make_box("", {0.40f, 0.40f, 0.0f}, {0.05f, 0.07f, 1.62f});
  append_mesh(chassis, make_box("", {-0.40f, 0.40f, 0.0f}, {0.05f, 0.07f, 1.62f}));
  for (const float zc : {axle, -axle})
    append_mesh(chassis,
                make_cylinder("", {-0.60f, kAxleHeight, zc}, x, 0.05f, 0.05f, 1.2f, half_segs));
  parts.push_back(part(prefix, "chassis", kSteel, std::move(chassis)));

  // The tub is open: floor, side walls, rear wall, dash, and flat rear fenders
  // over the wheels. Pieces overlap rather than share corners, so the merged
  // mesh stays closed after welding.
  Mesh body = make_box("", {0.0f, 0.50f, -0.575f}, {0.62f, 0.05f, 0.875f});
  for (const float side : {1.0f, -1.0f}) {
    append_mesh(body, make_box("", {side * 0.59f, 0.76f, -0.575f}, {0.03f, 0.26f, 0.875f}));
    append_mesh(body, make_box("", {side * 0.70f, 0.82f, -1.0f}, {0.11f, 0.02f, 0.46f}));
  }
  append_mesh(body, make_box("", {0.0f, 0.76f, -1.42f}, {0.57f, 0.26f, 0.03f}));
  append_mesh(body, make_box("", {0.0f, 0.78f, 0.27f}, {0.57f, 0.28f, 0.03f}));
  parts.push_back(part(prefix, "body", kOlive, std::move(body)));

  // Bonnet over the engine, with flat front fenders over the front wheels.
  Mesh bonnet = make_box("", {0.0f, 0.82f, 0.90f}, {0.50f, 0.24f, 0.62f});
  for (const float side : {1.0f, -1.0f})
    append_mesh(bonnet, make_box("", {side * 0.66f, 0.80f, 0.98f}, {0.16f, 0.025f, 0.56f}));
  parts.push_back(part(prefix, "bonnet", kOlive, std::move(bonnet)));

  // Grille panel with the slotted look of the Willys: dark slats standing proud.
  parts.push_back(part(prefix, "grille", kDarkOlive,
                       make_box("", {0.0f, 0.78f, 1.545f}, {0.46f, 0.26f, 0.025f})));
  Mesh slats = make_box("", {-0.16f, 0.70f, 1.575f}, {0.018f, 0.15f, 0.01f});
  for (int i = 1; i < 9; ++i)
    append_mesh(slats,
                make_box("", {-0.16f + 0.04f * float(i), 0.70f, 1.575f}, {0.012f, 0.15f, 0.01f}));
  parts.push_back(part(prefix, "grille_slats", kSteel, std::move(slats)));
  Mesh lamps = make_cylinder("", {0.32f, 0.88f, 1.55f}, z, 0.085f, 0.085f, 0.05f, half_segs);
  append_mesh(lamps,
              make_cylinder("", {-0.32f, 0.88f, 1.55f}, z, 0.085f, 0.085f, 0.05f, half_segs));
  parts.push_back(part(prefix, "headlights", kLamp, std::move(lamps)));

  parts.push_back(part(prefix, "bumper_front", kDarkOlive,
                       make_box("", {0.0f, 0.46f, 1.64f}, {0.82f, 0.07f, 0.05f})));
  parts.push_back(part(prefix, "bumper_rear", kDarkOlive,
                       make_box("", {0.0f, 0.40f, -1.62f}, {0.75f, 0.06f, 0.04f})));

  // Windscreen frame (no glass) on the dash, leaning back 10°.
  {
    const glm::mat3 lean = rotation_x(-10.0f);
    const glm::vec3 hinge(0.0f, 1.06f, 0.27f);
    const auto bar = [&](glm::vec3 c, glm::vec3 h) {
      return make_box("", hinge + lean * c, h, lean);
    };
    Mesh frame = bar({0.0f, 0.03f, 0.0f}, {0.72f, 0.03f, 0.025f});
    append_mesh(frame, bar({0.0f, 0.48f, 0.0f}, {0.72f, 0.03f, 0.025f}));
    append_mesh(frame, bar({0.69f, 0.255f, 0.0f}, {0.03f, 0.24f, 0.02f}));
    append_mesh(frame, bar({-0.69f, 0.255f, 0.0f}, {0.03f, 0.24f, 0.02f}));
    parts.push_back(part(prefix, "windscreen", kDarkOlive, std::move(frame)));
  }

  // Roll bar: a hoop behind the seats braced back to the rear corners.
  {
    const float r = 0.03f, hoop_z = -0.72f, top = 1.68f;
    Mesh bar = make_cylinder("", {-0.63f, top, hoop_z}, x, r, r, 1.26f, half_segs);
    for (const float side : {1.0f, -1.0f}) {
      append_mesh(
          bar, make_cylinder("", {side * 0.59f, 0.95f, hoop_z}, y, r, r, top - 0.95f, half_segs));
      const glm::vec3 from(side * 0.59f, 1.60f, hoop_z - 0.02f);
      const glm::vec3 to(side * 0.59f, 1.00f, -1.40f);
      append_mesh(bar, make_cylinder("", from, to - from, r, r, glm::length(to - from), half_segs));
    }
    parts.push_back(part(prefix, "roll_bar", kSteel, std::move(bar)));
  }

  // Two bucket seats: pedestal, cushion, back.
  {
    Mesh seats;
    for (const float side : {1.0f, -1.0f}) {
      append_mesh(seats, make_box("", {side * 0.33f, 0.60f, -0.35f}, {0.15f, 0.06f, 0.15f}));
      append_mesh(seats, make_box("", {side * 0.33f, 0.72f, -0.35f}, {0.22f, 0.06f, 0.24f}));
      append_mesh(seats, make_box("", {side * 0.33f, 1.00f, -0.62f}, {0.22f, 0.25f, 0.04f},
                                  rotation_x(-8.0f)));
    }
    parts.push_back(part(prefix, "seats", kSeat, std::move(seats)));
  }

  // Steering wheel on the left (driver's) side, column raked through the dash.
  {
    const glm::vec3 axis = glm::normalize(glm::vec3(0.0f, 0.7f, -0.7f));
    const glm::vec3 hub(0.33f, 1.10f, 0.0f);
    Mesh wheel = make_torus("", hub, axis, 0.18f, 0.018f, segs, quarter_segs);
    append_mesh(wheel,
                make_cylinder("", hub - 0.45f * axis, axis, 0.025f, 0.025f, 0.45f, half_segs));
    parts.push_back(part(prefix, "steering", kSteel, std::move(wheel)));
  }
  return parts;
}

namespace {

// Camera distance along -forward from `target` at which every point lies
// inside a frame of half-angle tangents (tan_x, tan_y).
float fit_distance(const std::vector<glm::vec3>& points, glm::vec3 target, glm::vec3 forward,
                   glm::vec3 right, glm::vec3 up, float tan_x, float tan_y) {
  float d = 0.0f;
  for (const auto& q : points) {
    const glm::vec3 rel = q - target;
    const float depth = glm::dot(rel, forward);
    d = std::max({d, std::fabs(glm::dot(rel, right)) / tan_x - depth,
                  std::fabs(glm::dot(rel, up)) / tan_y - depth});
  }
  return d;
}

Scene build_jeeps(const Params& p) {
  const int count = p.get_int("count");
  const bool rows_layout = p.get_string("layout") == "rows";
  const float spacing = p.get_float("spacing");
  const int tessellation = p.get_int("tessellation");
  const float light_size = p.get_float("light_size");
  const int seed = p.get_int("seed");

  Scene s;
  s.name = "jeep";

  // Pitch from the footprint a jeep can reach when yawed and offset, so that
  // neighbours' bounding boxes keep at least `spacing` between them.
  Bounds local;
  for (const auto& m : make_jeep("probe", tessellation))
    for (const auto& v : m.positions) local.extend(v);
  const float reach_x0 = std::max(-local.lo.x, local.hi.x);
  const float reach_z0 = std::max(-local.lo.z, local.hi.z);
  const float max_yaw = seed != 0 ? glm::radians(8.0f) : 0.0f;
  const float jitter = seed != 0 ? 0.2f * spacing : 0.0f;
  const float reach_x = reach_x0 + reach_z0 * std::sin(max_yaw);
  const float reach_z = reach_z0 + reach_x0 * std::sin(max_yaw);
  const float pitch_x = 2.0f * (reach_x + jitter) + spacing;
  const float pitch_z = 2.0f * (reach_z + jitter) + spacing;
  const int cols =
      rows_layout ? std::min(count, 8) : int(std::ceil(std::sqrt(double(count)) - 1e-9));
  const int rows = (count + cols - 1) / cols;

  for (int i = 0; i < count; ++i) {
    const int col = i % cols, row = i / cols;
    glm::vec3 pos((float(col) - 0.5f * float(cols - 1)) * pitch_x, 0.0f,
                  (0.5f * float(rows - 1) - float(row)) * pitch_z);  // row 0 in front
    float yaw = 0.0f;
    if (seed != 0) {
      // One stream per (seed, jeep), independent of the library (core/counter_rng.h).
      const uint64_t stream = uint64_t(uint32_t(seed)) * 0x100000001B3ull + uint64_t(i);
      yaw = (2.0f * core::uniform_float(stream, 0) - 1.0f) * max_yaw;
      pos.x += (2.0f * core::uniform_float(stream, 1) - 1.0f) * jitter;
      pos.z += (2.0f * core::uniform_float(stream, 2) - 1.0f) * jitter;
    }
    const glm::mat4 place = glm::rotate(glm::translate(glm::mat4(1.0f), pos), yaw, {0, 1, 0});
    for (auto& m : make_jeep("jeep_" + std::to_string(i), tessellation)) {
      transform_mesh(m, place);
      s.meshes.push_back(std::move(m));
    }
  }
  const Bounds set = s.caster_bounds();
  const glm::vec3 center = set.center();

  // Light above, to the front-right of the set, ~50° up: shadows fall back-left.
  const float light_distance = std::max(18.0f, 3.0f * set.radius());
  const glm::vec3 to_light = glm::normalize(glm::vec3(-0.45f, 0.77f, 0.45f));
  s.light = make_area_light(center + light_distance * to_light, center, light_size, light_size);

  // Frame the jeeps and the shadows of their tops (traced from the light's
  // centre onto the ground, one light size wider for the penumbra).
  std::vector<glm::vec3> points;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c((i & 1) ? set.hi.x : set.lo.x, (i & 2) ? set.hi.y : set.lo.y,
                      (i & 4) ? set.hi.z : set.lo.z);
    points.push_back(c);
    if (i & 2) {
      const glm::vec3 l = s.light.center;
      const glm::vec3 g = c + (c - l) * (c.y / (l.y - c.y));
      const glm::vec3 away = glm::normalize(glm::vec3(g.x - c.x, 0.0f, g.z - c.z));
      points.push_back(g + 0.5f * light_size * away);
    }
  }
  const float azimuth = glm::radians(30.0f), elevation = glm::radians(40.0f);
  const glm::vec3 to_eye(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                         std::cos(azimuth) * std::cos(elevation));
  const glm::vec3 forward = -to_eye;
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  s.camera.fov_y_degrees = 45.0f;
  // 8% margin inside a 4:3 frame.
  const float tan_y = 0.92f * std::tan(glm::radians(0.5f * s.camera.fov_y_degrees));
  const float tan_x = tan_y * 4.0f / 3.0f;
  glm::vec3 target = center;
  float distance = 0.0f;
  // Re-centre the target on the projected extent a few times, then fit exactly.
  for (int iteration = 0; iteration < 4; ++iteration) {
    distance = fit_distance(points, target, forward, right, up, tan_x, tan_y);
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const auto& q : points) {
      const glm::vec3 rel = q - target;
      const float depth = distance + glm::dot(rel, forward);
      const glm::vec2 ndc(glm::dot(rel, right) / (depth * tan_x),
                          glm::dot(rel, up) / (depth * tan_y));
      lo = glm::min(lo, ndc);
      hi = glm::max(hi, ndc);
    }
    const glm::vec2 mid = 0.5f * (lo + hi);
    target += distance * (mid.x * tan_x * right + mid.y * tan_y * up);
  }
  distance = fit_distance(points, target, forward, right, up, tan_x, tan_y);
  s.camera.target = target;
  s.camera.eye = target + distance * to_eye;
  float nearest = 1e30f;
  for (const auto& q : points) nearest = std::min(nearest, glm::dot(q - s.camera.eye, forward));
  s.camera.near_plane = std::max(0.01f, 0.25f * nearest);

  // The ground must reach every corner ray, also for frames wider than 4:3.
  const float wide_x = 2.0f * std::tan(glm::radians(0.5f * s.camera.fov_y_degrees));
  const float tall_y = std::tan(glm::radians(0.5f * s.camera.fov_y_degrees));
  float far_plane = 2.0f * (distance + set.radius());
  float half_size = 2.0f * set.radius() + 10.0f;
  for (const float sx : {-1.0f, 1.0f})
    for (const float sy : {-1.0f, 1.0f}) {
      const glm::vec3 ray = forward + sx * wide_x * right + sy * tall_y * up;
      if (ray.y >= -1e-3f) continue;  // does not reach the ground (not at 40° down)
      const float t = s.camera.eye.y / -ray.y;
      const glm::vec3 hit = s.camera.eye + t * ray;
      far_plane = std::max(far_plane, 1.1f * t * glm::dot(ray, forward));
      half_size = std::max(
          half_size, 1.1f * std::max(std::fabs(hit.x - center.x), std::fabs(hit.z - center.z)));
    }
  s.camera.far_plane = far_plane;

  Mesh ground = make_ground_plane("ground", glm::vec3(center.x, 0.0f, center.z), half_size);
  ground.albedo = glm::vec3(0.78f, 0.74f, 0.64f);
  s.meshes.push_back(std::move(ground));
  return s;
}

}  // namespace

// One jeep makes at most 6t² + 64t + 700 triangles at tessellation t
// (measured: 1058 at 6, 3622 at 20, 26150 at 64, 96934 at 128).
std::pair<std::string, std::string> check_jeeps(const Params& p) {
  const uint64_t t = uint64_t(p.get_int("tessellation"));
  return triangle_budget(budget_mul(uint64_t(p.get_int("count")), 6 * t * t + 64 * t + 700),
                         "count");
}

SceneType jeep_scene_type() {
  return {"jeep",
          "count procedural jeeps (~3600 triangles each) over a ground plane, square area light "
          "(Atty et al. 2006, Eisemann & Décoret 2008)",
          {int_param("count", 1, 1, 1024, "number of jeeps"),
           choice_param("layout", "grid", {"grid", "rows"},
                        "grid: ceil(sqrt(count)) jeeps per row; rows: 8 per row, side by side"),
           float_param("spacing", 1.0, 0.0, 1e3,
                       "smallest gap between neighbouring jeeps' bounding boxes"),
           int_param("tessellation", 20, 6, 128,
                     "segments of round parts (tubes and tyre cross-sections get half)"),
           float_param("light_size", 2.0, 0.0, 1e4, "side of the square area light"),
           int_param("seed", 1, 0, 2147483647,
                     "per-jeep yaw (up to 8°) and offset (up to 0.2*spacing); 0 = aligned")},
          build_jeeps,
          check_jeeps};
}

}  // namespace sb
