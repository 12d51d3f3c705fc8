// outdoor — a square of ground `extent` metres on a side, a road along its
// middle (x ∈ [−4, 4], running along z), and on it, from a seed:
//
// - buildings (closed boxes, some with a narrower tier on top, a few of them
//   towers): half along the road, their fronts 11 to 17 m from its axis,
//   half anywhere off it, turned at random;
// - trees (a closed trunk and limbs, `leaves` alpha-masked double-sided leaf
//   quads in an ellipsoidal crown): half on the verges (6.5 to 8 m from the
//   axis), half anywhere off the road, none inside a building's footprint;
// - poles: half street lights along both road edges, evenly spaced from the
//   camera to the far end; half power poles (0.16 m radius, 9–12 m, with a
//   cross-arm) and sign posts (0.035 m radius, 2–3 m, a 0.6 m plate)
//   anywhere off the road.
//
// The densities are per square kilometre, so the counts follow the area.
// Buildings are placed first, then trees clear of them, then poles clear of
// both. Each kind draws from its own stream of the seed (each tree's leaves
// from one of their own): a density never moves a kind placed before it
// (the kinds placed after it move out of its way, and keep their counts
// while there is room), and a larger density keeps the smaller one's
// objects and adds more (but for the street lights, spaced evenly).
//
// Whatever the densities, the camera's near field holds a sign post 3 m
// ahead, two bollards, a tree whose crown overhangs the view 6–11 m ahead
// and a building 20 m ahead on the right: casters a few metres away, whose
// shadows need a map's resolution near the camera, while the rest reach to
// the far end of the ground.
//
// The camera stands on the right verge (x = 5) 10 m in from the near edge,
// its eye 1.7 m up, looking along the road (−z) turned 4° towards it and
// 3° down; 55° vertical field of view, near plane 0.2 m, far plane 1.5 ×
// extent (past the ground's farthest corner). The sun stands at
// `sun_elevation` above the horizon, at `sun_azimuth` clockwise from the
// view direction seen from above (0: ahead, 90: to the right, 240: behind
// on the left, shadows falling ahead to the right, across the road).
#include "scenes/outdoor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/counter_rng.h"
#include "scenes/draws.h"
#include "scenes/leaf.h"
#include "scenes/outdoor_parts.h"
#include "scenes/triangle_budget.h"

namespace sb {

using core::AlphaMode;
using core::float_param;
using core::int_param;
using core::make_sun_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

constexpr float kRoadHalf = 4.0f;      // the road: |x| <= 4
constexpr float kLightX = 4.5f;        // street lights, both sides
constexpr float kFront = 11.0f;        // the nearest a building's front stands to the axis
constexpr float kEyeX = 5.0f;          // the camera, on the right verge
constexpr float kEyeHeight = 1.7f;     // a pedestrian's eye
constexpr float kEyeFromEdge = 10.0f;  // from the ground's near edge

// The sun's default diameter as the docs print it: kSunDiameterDegrees in
// a double, not the float's 0.52999997.
constexpr double kSunDiameter = 0.53;
static_assert(float(kSunDiameter) == core::kSunDiameterDegrees);

// The draws' streams: one per kind, derived from the seed.
enum Stream : uint64_t { kBuildings = 1, kTrees = 2, kPoles = 3, kLeaves = 4 };

// Circles on the ground (x, z, radius) in a hashed grid, to keep objects
// apart without comparing every pair.
class Footprints {
 public:
  bool free(glm::vec2 at, float radius, float gap) const {
    const int span = int(std::ceil((radius + largest_ + gap) / kCell));
    const auto [cx, cz] = cell(at);
    for (int i = cx - span; i <= cx + span; ++i)
      for (int j = cz - span; j <= cz + span; ++j) {
        const auto it = cells_.find(key(i, j));
        if (it == cells_.end()) continue;
        for (const glm::vec3& c : it->second)
          if (glm::length(at - glm::vec2(c.x, c.y)) < radius + c.z + gap) return false;
      }
    return true;
  }
  void add(glm::vec2 at, float radius) {
    const auto [cx, cz] = cell(at);
    cells_[key(cx, cz)].emplace_back(at.x, at.y, radius);
    largest_ = std::max(largest_, radius);
  }

 private:
  static constexpr float kCell = 48.0f;
  static std::pair<int, int> cell(glm::vec2 at) {
    return {int(std::floor(at.x / kCell)), int(std::floor(at.y / kCell))};
  }
  static int64_t key(int i, int j) { return (int64_t(i) << 32) ^ int64_t(uint32_t(j)); }
  std::unordered_map<int64_t, std::vector<glm::vec3>> cells_;
  float largest_ = 0.0f;
};

// The number of objects of a density (per km²) on `extent`².
uint64_t count_of(double per_km2, double extent) {
  return uint64_t(std::llround(per_km2 * extent * extent * 1e-6));
}

Mesh named(const std::string& name, glm::vec3 albedo) {
  Mesh m;
  m.name = name;
  m.albedo = albedo;
  return m;
}

// A rectangle of the ground y = 0 facing +y.
void add_rect(Mesh& m, float x0, float x1, float z0, float z1) {
  const auto base = uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), {{x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}});
  m.normals.insert(m.normals.end(), 4, glm::vec3(0, 1, 0));
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

struct Layout {
  Layout(const Params& params, uint64_t seed_, float half_, glm::vec2 eye_)
      : p(params), seed(seed_), half(half_), eye(eye_) {}
  const Params& p;
  uint64_t seed;
  float half;     // of the ground's side
  glm::vec2 eye;  // the camera's place on the ground (x, z)
  std::vector<Mesh> buildings;
  Mesh wood = named("trees/wood", glm::vec3(0.36f, 0.25f, 0.15f));
  Mesh leaves = named("leaves", glm::vec3(1.0f));
  Mesh poles = named("poles", glm::vec3(0.35f, 0.36f, 0.38f));
  Footprints solid;   // buildings: nothing else stands in them
  Footprints trunks;  // trunks and poles: no pole inside another or a trunk
  uint64_t trees_grown = 0;

  TreeShape tree_shape(float trunk_height, float trunk_radius, float crown) const {
    return {trunk_height, trunk_radius, crown, p.get_int("leaves"), p.get_float("leaf_size")};
  }
  bool on_ground(glm::vec2 at, float radius) const {
    return std::fabs(at.x) + radius <= half && std::fabs(at.y) + radius <= half;
  }
  void grow(glm::vec2 at, const TreeShape& shape) {
    Draws draws(core::splitmix64(core::splitmix64(seed, kLeaves), trees_grown++));
    add_tree(wood, leaves, at, shape, draws);
    trunks.add(at, shape.trunk_radius);
  }

  // Independent of the densities: the casters within a few metres.
  void near_field() {
    const glm::vec2 building(kFront + 6.0f, eye.y - 28.0f);
    add_building(buildings[0], building, 6.0f, 8.0f, 12.0f, 0.0f, 0.0f);
    solid.add(building, 10.0f);
    const glm::vec2 sign(eye.x + 0.9f, eye.y - 3.2f);
    add_sign_post(poles, sign, 2.4f, 0.35f);
    trunks.add(sign, 0.35f);
    for (const float ahead : {1.5f, 3.5f}) {
      const glm::vec2 bollard(kRoadHalf + 0.3f, eye.y - ahead);
      add_bollard(poles, bollard);
      trunks.add(bollard, 0.1f);
    }
    grow({eye.x + 2.2f, eye.y - 8.5f}, tree_shape(3.0f, 0.25f, 2.6f));
  }

  void street_lights(uint64_t n) {
    const float first = eye.y - 6.0f, last = -half + 3.0f;
    for (uint64_t k = 0; k < n; ++k) {
      const float z = n == 1 ? first : first + (last - first) * float(k) / float(n - 1);
      const float side = k % 2 == 0 ? 1.0f : -1.0f;  // the first on the camera's side
      const glm::vec2 at(side * kLightX, z);
      add_street_light(poles, at, glm::vec2(-side, 0.0f));
      trunks.add(at, 0.1f);
    }
  }

  void place_buildings(uint64_t n) {
    Draws d(core::splitmix64(seed, kBuildings));
    uint64_t placed = 0;
    for (uint64_t attempt = 0; placed < n && attempt < 30 * n + 100; ++attempt) {
      const bool roadside = d.chance(0.5f);
      const float hx = d.uniform(4.0f, 12.0f), hz = d.uniform(4.0f, 12.0f);
      float height = d.uniform(4.0f, 16.0f);
      if (d.chance(0.12f)) height += d.uniform(10.0f, 45.0f);  // a tower
      const float tier = d.chance(0.3f) ? d.uniform(2.0f, 0.5f * height) : 0.0f;
      const float side = d.chance(0.5f) ? 1.0f : -1.0f;
      const float setback = d.uniform(0.0f, 6.0f);
      const float u = d.uniform(-1.0f, 1.0f), v = d.uniform(-1.0f, 1.0f);
      const float turn = d.uniform(0.0f, 0.5f * std::numbers::pi_v<float>);
      const float r = std::sqrt(hx * hx + hz * hz);
      const glm::vec2 at = roadside ? glm::vec2(side * (kFront + setback + hx), u * half)
                                    : glm::vec2(u * half, v * half);
      if (!roadside && std::fabs(at.x) - r < kFront) continue;
      if (!on_ground(at, r + 1.0f) || glm::length(at - eye) < r + 8.0f) continue;
      if (!solid.free(at, r, 3.0f)) continue;
      add_building(buildings[placed % buildings.size()], at, hx, hz, height, roadside ? 0.0f : turn,
                   tier);
      solid.add(at, r);
      ++placed;
    }
  }

  void place_trees(uint64_t n) {
    Draws d(core::splitmix64(seed, kTrees));
    const float leaf_size = p.get_float("leaf_size");
    uint64_t placed = 0;
    for (uint64_t attempt = 0; placed < n && attempt < 30 * n + 100; ++attempt) {
      const bool roadside = d.chance(0.5f);
      const float side = d.chance(0.5f) ? 1.0f : -1.0f;
      const float verge = d.uniform(6.5f, 8.0f);
      const float u = d.uniform(-1.0f, 1.0f), v = d.uniform(-1.0f, 1.0f);
      const float trunk_height = d.uniform(2.0f, 4.0f), trunk_radius = d.uniform(0.12f, 0.3f);
      const float crown = roadside ? d.uniform(1.8f, 2.8f) : d.uniform(1.8f, 3.5f);
      const glm::vec2 at =
          roadside ? glm::vec2(side * verge, u * half) : glm::vec2(u * half, v * half);
      if (!roadside && std::fabs(at.x) - crown < kRoadHalf + 1.0f) continue;
      if (!on_ground(at, crown + leaf_size) || glm::length(at - eye) < crown + 1.0f) continue;
      if (!solid.free(at, crown, 0.5f) || !trunks.free(at, trunk_radius, 0.5f)) continue;
      grow(at, tree_shape(trunk_height, trunk_radius, crown));
      ++placed;
    }
  }

  void place_poles(uint64_t n) {
    Draws d(core::splitmix64(seed, kPoles));
    uint64_t placed = 0;
    for (uint64_t attempt = 0; placed < n && attempt < 30 * n + 100; ++attempt) {
      const bool power = d.chance(0.5f);
      const float u = d.uniform(-1.0f, 1.0f), v = d.uniform(-1.0f, 1.0f);
      const float height = power ? d.uniform(9.0f, 12.0f) : d.uniform(2.0f, 3.0f);
      const float yaw = d.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      const float reach = power ? 1.3f : 0.35f;  // the cross-arm's, the plate's
      const glm::vec2 at(u * half, v * half);
      if (std::fabs(at.x) < kRoadHalf + reach || !on_ground(at, reach + 1.0f)) continue;
      if (glm::length(at - eye) < reach + 1.5f) continue;
      if (!solid.free(at, reach, 0.5f) || !trunks.free(at, reach, 0.3f)) continue;
      if (power)
        add_power_pole(poles, at, height, yaw);
      else
        add_sign_post(poles, at, height, yaw);
      trunks.add(at, reach);
      ++placed;
    }
  }
};

Scene build_outdoor(const Params& p) {
  const float extent = p.get_float("extent");
  const float half = 0.5f * extent;
  Scene s;
  s.name = "outdoor";
  const auto seed = static_cast<uint64_t>(p.get_int("seed"));
  s.textures.push_back(make_leaf_texture(64, static_cast<uint32_t>(seed)));

  Layout l(p, seed, half, glm::vec2(kEyeX, half - kEyeFromEdge));
  for (const glm::vec3 albedo : {glm::vec3(0.72f, 0.70f, 0.66f), glm::vec3(0.62f, 0.36f, 0.28f),
                                 glm::vec3(0.84f, 0.78f, 0.62f), glm::vec3(0.88f, 0.88f, 0.86f)})
    l.buildings.push_back(named("buildings_" + std::to_string(l.buildings.size()), albedo));
  l.leaves.base_color_texture = 0;
  l.leaves.alpha_mode = AlphaMode::Mask;
  l.leaves.alpha_cutoff = 0.5f;
  l.leaves.double_sided = true;

  l.near_field();
  l.place_buildings(count_of(p.get_float("buildings"), extent));
  l.place_trees(count_of(p.get_float("trees"), extent));
  const uint64_t poles = count_of(p.get_float("poles"), extent);
  l.street_lights(poles / 2);
  l.place_poles(poles - poles / 2);

  std::vector<Mesh> casters = std::move(l.buildings);
  casters.push_back(std::move(l.wood));
  casters.push_back(std::move(l.leaves));
  casters.push_back(std::move(l.poles));
  for (Mesh& m : casters)  // an empty one (no leaves, no buildings of a colour) draws nothing
    if (!m.indices.empty()) s.meshes.push_back(std::move(m));
  // Receivers under everything: they occlude nothing.
  Mesh ground = named("ground", glm::vec3(0.42f, 0.46f, 0.30f));
  add_rect(ground, -half, -kRoadHalf, -half, half);
  add_rect(ground, kRoadHalf, half, -half, half);
  ground.casts_shadow = false;
  Mesh road = named("road", glm::vec3(0.24f, 0.24f, 0.26f));
  add_rect(road, -kRoadHalf, kRoadHalf, -half, half);
  road.casts_shadow = false;
  s.meshes.push_back(std::move(ground));
  s.meshes.push_back(std::move(road));

  const float el = glm::radians(p.get_float("sun_elevation"));
  const float az = glm::radians(p.get_float("sun_azimuth"));
  const glm::vec3 to_sun(std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az));
  s.light = make_sun_light(to_sun, glm::vec3(0.0f), glm::radians(p.get_float("sun_diameter")),
                           2.0f * extent);

  s.camera.eye = glm::vec3(l.eye.x, kEyeHeight, l.eye.y);
  const float yaw = glm::radians(4.0f), pitch = glm::radians(3.0f);
  const glm::vec3 view(-std::sin(yaw) * std::cos(pitch), -std::sin(pitch),
                       -std::cos(yaw) * std::cos(pitch));
  s.camera.target = s.camera.eye + 100.0f * view;
  s.camera.fov_y_degrees = 55.0f;
  s.camera.near_plane = 0.2f;
  s.camera.far_plane = 1.5f * extent;
  return s;
}

}  // namespace

// Every kind at its most triangles per object, the near field's own, and
// the ground; blames the density of the kind that adds the most.
std::pair<std::string, std::string> check_outdoor(const Params& p) {
  const double extent = p.get_float("extent");
  const uint64_t per_tree = kTreeWoodTriangles + 2 * uint64_t(p.get_int("leaves"));
  const uint64_t buildings =
      budget_mul(count_of(p.get_float("buildings"), extent), kBuildingTriangles);
  const uint64_t trees = budget_mul(count_of(p.get_float("trees"), extent), per_tree);
  const uint64_t poles = budget_mul(count_of(p.get_float("poles"), extent), kPoleTriangles);
  const uint64_t near = kBuildingTriangles + 3 * kPoleTriangles + per_tree + 6;
  const uint64_t total = std::max({buildings, trees, poles}) == UINT64_MAX
                             ? UINT64_MAX
                             : buildings + trees + poles + near;
  const char* blame = trees >= buildings && trees >= poles ? "trees"
                      : buildings >= poles                 ? "buildings"
                                                           : "poles";
  return triangle_budget(total, blame);
}

SceneType outdoor_scene_type() {
  return {
      "outdoor",
      "a kilometre of ground under the sun seen from a pedestrian's eye: buildings, trees with "
      "alpha-masked leaves and poles from centimetres to tens of metres, from the camera's feet to "
      "the far end",
      {int_param("seed", 1, 0, 2147483647, "generator seed (same seed, same scene)"),
       float_param("extent", 1000.0, 1000.0, 20000.0,
                   "side of the square ground, in metres; the road runs its length"),
       float_param("buildings", 150.0, 0.0, 5000.0, "buildings per km²"),
       float_param("trees", 400.0, 0.0, 20000.0, "trees per km²"),
       float_param("poles", 150.0, 0.0, 20000.0,
                   "poles per km²: half street lights along the road, half power poles and sign "
                   "posts"),
       int_param("leaves", 100, 0, 1000, "leaf quads per tree"),
       float_param("leaf_size", 0.5, 0.05, 3.0, "leaf quad side, in metres"),
       float_param("sun_elevation", 35.0, 1.0, 90.0, "the sun's height above the horizon, degrees"),
       float_param("sun_azimuth", 240.0, 0.0, 360.0,
                   "the sun's direction seen from above, degrees clockwise from the view "
                   "direction (240: behind on the left)"),
       float_param("sun_diameter", kSunDiameter, 0.0, 20.0, "the sun's angular diameter, degrees")},
      build_outdoor,
      check_outdoor};
}

}  // namespace sb
