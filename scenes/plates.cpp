// plates — stiff cases for soft-shadow filters: a straight occluder edge, and
// stacked occluders. Thin closed boxes ("plates") over a ground plane under a
// square area light that faces straight down.
//
// | parameter    | default | meaning                                                       |
// |--------------|---------|---------------------------------------------------------------|
// | layout       | "edge"  | edge: one plate with a straight edge; stacked: two plates     |
// | height       | 1.0     | mid-plane of the (lower) plate; must exceed thickness / 2     |
// | upper_height | 4.0     | stacked only: mid-plane of the upper plate; must exceed       |
// |              |         | height + thickness (the plates may not touch)                 |
// | thickness    | 0.05    | of every plate                                                |
// | light_size   | 1.0     | side of the square area light                                 |
// | light_height | 8.0     | height of the light; must exceed the top of the highest plate |
//
// Invalid combinations are bad input, found when a config or a scene spec is
// loaded (SceneType::check) and named by the parameter's JSON pointer.
//
// edge. One plate over x ∈ [−d, 0], z ∈ [−w, w] (mesh "plate"), with
// d = max(3, light_size): its straight edge runs along z at x = 0, and w (at
// least 3) reaches past the ground that any frame up to 2:1 shows, so the edge
// is straight across the whole view. The light is centred at
// (−d, light_height, 0), so the edge's shadow falls on open ground at x > 0.
// With e = height + thickness / 2 (the plate's top edge is the one that
// bounds the shadow) and k = e / (light_height − e), the light's extreme x,
// −d ± light_size / 2, put the penumbra on the ground at
// x ∈ [(d − light_size/2)·k, (d + light_size/2)·k]: [0.367, 0.514] for
// light_size 1 and [0.220, 0.661] for 3 at the defaults. The camera looks
// along −z, 55° down, at the penumbra's centre line x = d·k, which is the
// image's vertical centre line; it frames d·k, but at least e (the eye stays
// above the plate), either side of it, so the penumbra of a light of size d
// spans at most the middle half of the image width. Light and camera do not
// move for light sizes up to 3, so a sweep of light_size only widens the
// penumbra.
//
// stacked. A lower plate over x, z ∈ [−2, 2] at `height` ("lower_plate") and
// an upper plate at `upper_height` ("upper_plate") covering x ≤ x_u. The light
// is centred above the origin. x_u is placed so that, seen from the light's
// centre, the upper edge projects onto the ground at x_b = 2 − min(1.5·height,
// 2), under the lower plate, where the ground is in the lower plate's umbra
// for light sizes up to 4; the upper plate's other edges project 1.5 times
// the lower plate's half-size from the light's axis, outside it. A variance
// shadow map sees both plates' depths in the filter footprint around the
// projected edge and lets light bleed along that line. The camera stands off
// the lower plate's +x side and looks along −x in under it: the sight line to
// the ground at x_b passes under the lower plate's near edge at 60% of the gap
// (so image rows are lines of constant x, the bleeding line among them), the
// view is tilted down enough for every corner ray to meet the ground, and the
// lower plate's width fills the frame at the depth of the line.
#include "scenes/plates.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "core/error.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb {

using core::Bounds;
using core::Camera;
using core::choice_param;
using core::float_param;
using core::InputError;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

constexpr float kFovY = 45.0f;           // degrees, vertical
constexpr float kFrameFill = 0.92f;      // framed points stay inside 92% of the half-frame
constexpr float kMinEdgeHalfZ = 3.0f;    // the edge plate spans at least z ∈ [−3, 3]
constexpr float kMinReach = 3.0f;        // light offset (edge) and largest framed light size
constexpr float kEdgeElevation = 55.0f;  // degrees below the horizon, edge camera
constexpr float kLowerHalf = 2.0f;       // the stacked lower plate spans x, z ∈ [−2, 2]
constexpr float kUpperReach = 1.5f;      // upper plate's far edges, in lower half-sizes
const glm::vec3 kPlateAlbedo(0.45f, 0.52f, 0.62f);
const glm::vec3 kGroundAlbedo(0.8f, 0.78f, 0.74f);

// The parameters, read once.
struct Setup {
  bool stacked = false;
  float height = 0.0f;
  float upper_height = 0.0f;
  float thickness = 0.0f;
  float light_size = 0.0f;
  float light_height = 0.0f;
};

Setup read_setup(const Params& p) {
  return {p.get_string("layout") == "stacked", p.get_float("height"),
          p.get_float("upper_height"),         p.get_float("thickness"),
          p.get_float("light_size"),           p.get_float("light_height")};
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

Mesh plate(const std::string& name, glm::vec3 lo, glm::vec3 hi) {
  Mesh m = make_box(name, 0.5f * (lo + hi), 0.5f * (hi - lo));
  m.albedo = kPlateAlbedo;
  return m;
}

// Half-width tangent of the 4:3 frame, inside the fill margin.
float frame_tan_x() { return kFrameFill * std::tan(glm::radians(0.5f * kFovY)) * 4.0f / 3.0f; }

// Distance from `p` to the axis-aligned box of `b` (0 inside).
float distance_to(const Bounds& b, glm::vec3 p) {
  return glm::length(glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f)));
}

// Where the corner rays of the camera's frame of aspect `aspect` meet the
// ground; rays at or above the horizon (the background) are left out.
std::vector<glm::vec3> ground_corners(const Camera& c, float aspect) {
  const glm::vec3 forward = glm::normalize(c.target - c.eye);
  const glm::vec3 side = glm::normalize(glm::cross(forward, c.up));
  const glm::vec3 rise = glm::cross(side, forward);
  const float tan_y = std::tan(glm::radians(0.5f * c.fov_y_degrees));
  std::vector<glm::vec3> hits;
  for (int corner = 0; corner < 4; ++corner) {
    const float sx = (corner & 1) ? aspect : -aspect, sy = (corner & 2) ? 1.0f : -1.0f;
    const glm::vec3 ray = forward + tan_y * (sx * side + sy * rise);  // depth 1 along forward
    if (ray.y < -1e-3f) hits.push_back(c.eye + (c.eye.y / -ray.y) * ray);
  }
  return hits;
}

// Sets the camera's near and far planes and adds a ground quad under `center`
// that every downward corner ray of frames up to 2:1 meets before the far plane.
void finish_view(Scene& s, glm::vec3 center) {
  Camera& c = s.camera;
  const float clearance = std::min(c.eye.y, distance_to(s.caster_bounds(), c.eye));
  c.near_plane = std::max(1e-3f, 0.5f * clearance);
  const glm::vec3 forward = glm::normalize(c.target - c.eye);
  float far_plane = 4.0f * glm::length(c.target - c.eye);
  float half_size = 10.0f + glm::length(c.eye - center);
  for (const glm::vec3& hit : ground_corners(c, 2.0f)) {
    far_plane = std::max(far_plane, 1.1f * glm::dot(hit - c.eye, forward));
    half_size = std::max(half_size,
                         1.1f * std::max(std::fabs(hit.x - center.x), std::fabs(hit.z - center.z)));
  }
  c.far_plane = far_plane;
  Mesh ground = make_ground_plane("ground", glm::vec3(center.x, 0.0f, center.z), half_size);
  ground.albedo = kGroundAlbedo;
  s.meshes.push_back(std::move(ground));
}

void build_edge(Scene& s, const Setup& d) {
  const float reach = std::max(kMinReach, d.light_size);
  const float edge_y = d.height + 0.5f * d.thickness;
  const float k = edge_y / (d.light_height - edge_y);

  // Penumbra centre line x = reach·k at the image's centre; reach·k (at
  // least the edge's height, so the eye stays above the plate) either side.
  const glm::vec3 center(reach * k, 0.0f, 0.0f);
  const float half_width = std::max(reach * k, edge_y);
  const float elevation = glm::radians(kEdgeElevation);
  const glm::vec3 to_eye(0.0f, std::sin(elevation), std::cos(elevation));
  s.camera.fov_y_degrees = kFovY;
  s.camera.target = center;
  s.camera.eye = center + (half_width / frame_tan_x()) * to_eye;

  // The plate reaches past the ground any frame up to 2:1 shows, so that its
  // edge is straight across the whole view.
  float half_z = kMinEdgeHalfZ;
  for (const glm::vec3& hit : ground_corners(s.camera, 2.0f))
    half_z = std::max(half_z, 1.1f * std::fabs(hit.z) + 0.5f);
  s.meshes.push_back(plate("plate", glm::vec3(-reach, d.height - 0.5f * d.thickness, -half_z),
                           glm::vec3(0.0f, edge_y, half_z)));
  s.light = make_area_light(glm::vec3(-reach, d.light_height, 0.0f), glm::vec3(-reach, 0.0f, 0.0f),
                            d.light_size, d.light_size);
  finish_view(s, center);
}

void build_stacked(Scene& s, const Setup& d) {
  const float a = kLowerHalf, half_t = 0.5f * d.thickness, height = d.height;
  s.meshes.push_back(
      plate("lower_plate", glm::vec3(-a, height - half_t, -a), glm::vec3(a, height + half_t, a)));
  // Seen from the light's centre (0, light_height, 0), a point at height y
  // and horizontal offset x projects onto the ground at x·light_height /
  // (light_height − y) and onto the lower plate at x·(light_height − height)
  // / (light_height − y).
  const float depth_below_light = d.light_height - d.upper_height;
  const float bleed_x = a - std::min(1.5f * height, a);
  const float upper_x = bleed_x * depth_below_light / d.light_height;
  const float far_edge = kUpperReach * a * depth_below_light / (d.light_height - height);
  s.meshes.push_back(plate("upper_plate", glm::vec3(-far_edge, d.upper_height - half_t, -far_edge),
                           glm::vec3(upper_x, d.upper_height + half_t, far_edge)));
  s.light = make_area_light(glm::vec3(0.0f, d.light_height, 0.0f), glm::vec3(0.0f), d.light_size,
                            d.light_size);

  // The sight line from the bleeding line rises towards +x and passes under
  // the lower plate's near edge at 60% of the gap.
  const glm::vec3 bleed(bleed_x, 0.0f, 0.0f);
  const float rise = std::atan(0.6f * (height - half_t) / (a - bleed_x));
  const float half_fov = glm::radians(0.5f * kFovY);
  const float pitch = std::max(rise, half_fov + glm::radians(6.0f));
  const float distance = a / (frame_tan_x() * std::cos(pitch - rise));
  s.camera.fov_y_degrees = kFovY;
  s.camera.eye = bleed + distance * glm::vec3(std::cos(rise), std::sin(rise), 0.0f);
  const glm::vec3 forward(-std::cos(pitch), -std::sin(pitch), 0.0f);
  s.camera.target = s.camera.eye + (s.camera.eye.y / std::sin(pitch)) * forward;
  finish_view(s, bleed);
}

// The rules across parameters: {parameter to blame, what is wrong}, or "".
std::pair<std::string, std::string> check_plates(const Params& p) {
  const Setup d = read_setup(p);
  const auto expected = [](const std::string& what, float found) {
    return "expected a number greater than " + what + ", found " + number(found);
  };
  if (!(d.height - 0.5f * d.thickness > 0.0f))
    return {"height", expected("thickness / 2 (" + number(0.5f * d.thickness) + ")", d.height)};
  if (d.stacked && !(d.upper_height > d.height + d.thickness))
    return {"upper_height", expected("height + thickness (" + number(d.height + d.thickness) +
                                         ") with layout \"stacked\" (the plates may not touch)",
                                     d.upper_height)};
  const float top = (d.stacked ? d.upper_height : d.height) + 0.5f * d.thickness;
  if (!(d.light_height > top))
    return {"light_height",
            expected("the top of the highest plate (" + number(top) + ")", d.light_height)};
  return {};
}

Scene build_plates(const Params& p) {
  // Configs and scene specs are checked when loaded; this catches direct callers.
  if (const auto [param, problem] = check_plates(p); !problem.empty())
    throw InputError("", "/params/" + param, problem);
  const Setup d = read_setup(p);
  Scene s;
  s.name = "plates";
  if (d.stacked)
    build_stacked(s, d);
  else
    build_edge(s, d);
  return s;
}

}  // namespace

SceneType plates_scene_type() {
  return {"plates",
          "thin closed plates under a square area light facing down: a straight occluder edge "
          "(penumbra width) or stacked occluders (variance shadow map light bleeding)",
          {choice_param("layout", "edge", {"edge", "stacked"},
                        "edge: one plate with a straight edge; stacked: an upper plate whose edge "
                        "lies over a lower, larger plate"),
           float_param("height", 1.0, 1e-3, 1e4, "mid-plane height of the (lower) plate"),
           float_param("upper_height", 4.0, 1e-3, 1e4,
                       "stacked: mid-plane height of the upper plate (> height + thickness)"),
           float_param("thickness", 0.05, 1e-4, 1e2, "thickness of every plate"),
           float_param("light_size", 1.0, 0.0, 1e4, "side of the square area light"),
           float_param("light_height", 8.0, 1e-2, 1e5,
                       "height of the light (above the highest plate)")},
          build_plates,
          check_plates};
}

}  // namespace sb
