// Needs are named requests resolved by providers: the harness's and a
// plugin's alike, each computed only when a technique asks, after what it
// requires, and checked for its type when read. The silhouette-edge data is
// tested against the geometry itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "core/scene_types.h"
#include "plan/need_resolution.h"
#include "plugin/registry.h"
#include "scenes/mesh_builders.h"
#include "scenes/need_providers.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::Mesh;
using core::Scene;
using plan::Derive;
using plan::find_need_provider;
using plan::resolve_needs;
using plan::ResolvedNeeds;
using plugin::DerivedData;
using plugin::NeedProvider;
using plugin::Needs;
using plugin::Registry;
using plugin::TechniqueInfo;

namespace {

Scene box_on_ground() {
  Scene s;
  s.meshes.push_back(make_box("box", {0, 1, 0}, {0.5f, 1.0f, 1.5f}));
  s.meshes.push_back(make_ground_plane("ground", glm::vec3(0), 5.0f));
  s.meshes.back().casts_shadow = false;
  return s;
}

TechniqueInfo wanting(const std::string& name, Needs needs) {
  return {name, "test", "", std::move(needs), {}, nullptr};
}

// A plugin's need: counts its own computations, requires the harness's.
struct Counted {
  int derived = 0;
  std::vector<std::string> saw;  // the needs already present when it ran
};

NeedProvider counting_provider(Counted* c, NeedProvider::When when) {
  NeedProvider p;
  p.name = "caster_count";
  p.summary = "how many meshes cast";
  p.requires_needs = {plugin::need::kCasterClosedness};
  p.when = when;
  p.derive = [c](const Scene& scene, DerivedData& data, std::vector<std::string>& log) {
    ++c->derived;
    c->saw = data.names();
    int n = 0;
    for (const auto& m : scene.meshes) n += m.casts_shadow ? 1 : 0;
    data.put<int>("caster_count", std::make_shared<int>(n));
    log.emplace_back("counted casters");
  };
  if (when == NeedProvider::When::Plan)  // only Plan needs may skip
    p.unmet = [](const Scene&, const DerivedData& data) -> std::string {
      return data.get<int>("caster_count") > 0 ? "" : "needs a caster";
    };
  return p;
}

TEST(NeedProviders, APluginsNeedIsComputedOnlyWhenAskedAndAfterWhatItRequires) {
  Counted counted;
  Registry plugins;
  plugins.add_provider(counting_provider(&counted, NeedProvider::When::Plan));
  const Scene s = box_on_ground();
  const TechniqueInfo plain = wanting("plain", {});
  const TechniqueInfo counting = wanting("counting", {"caster_count"});

  ResolvedNeeds r = resolve_needs(s, {&plain}, &plugins, Derive::All);
  EXPECT_EQ(counted.derived, 0);
  EXPECT_FALSE(r.data.has("caster_count"));

  r = resolve_needs(s, {&plain, &counting, &counting}, &plugins, Derive::Decide);
  EXPECT_EQ(counted.derived, 1);  // once, however many techniques ask
  // What it requires was there before it ran (with the checks that every
  // technique has, such as the implied local_light).
  EXPECT_NE(std::find(counted.saw.begin(), counted.saw.end(), plugin::need::kCasterClosedness),
            counted.saw.end());
  EXPECT_EQ(std::find(counted.saw.begin(), counted.saw.end(), "caster_count"), counted.saw.end());
  EXPECT_EQ(r.data.get<int>("caster_count"), 1);
  EXPECT_EQ(r.skip_reason, (std::vector<std::string>{"", "", ""}));

  // Its check can skip a job, worded after the technique's name.
  Scene empty = s;
  empty.meshes[0].casts_shadow = false;
  r = resolve_needs(empty, {&counting}, &plugins, Derive::Decide);
  EXPECT_EQ(r.skip_reason[0], "counting needs a caster");
}

// A technique that names no sun need never runs under the sun; one that
// names sun_light runs only there; sun_or_local_light runs under both.
TEST(NeedProviders, TheSunSkipsTechniquesMadeForALightAtAPlace) {
  const TechniqueInfo plain = wanting("plain", {});
  const TechniqueInfo sun_only = wanting("cascades", {plugin::need::kSunLight});
  const TechniqueInfo both = wanting("either", {plugin::need::kSunOrLocalLight});
  Scene local = box_on_ground();
  Scene sun = local;
  sun.light = core::make_sun_light({0.3f, 1.0f, 0.2f}, {0, 0, 0}, glm::radians(0.53f), 30.0f);

  ResolvedNeeds r = resolve_needs(local, {&plain, &sun_only, &both}, nullptr, Derive::Decide);
  EXPECT_EQ(r.skip_reason[0], "");
  EXPECT_EQ(r.skip_reason[1].rfind("cascades needs the sun (light.type \"sun\"); the scene's light "
                                   "is a 1×1 rectangle",
                                   0),
            0u)
      << r.skip_reason[1];
  EXPECT_EQ(r.skip_reason[2], "");

  r = resolve_needs(sun, {&plain, &sun_only, &both}, nullptr, Derive::Decide);
  EXPECT_EQ(r.skip_reason[0],
            "plain needs a local light (a rectangle, a segment or a point); the scene's light is "
            "the sun (0.53°)");
  EXPECT_EQ(r.skip_reason[1], "");
  EXPECT_EQ(r.skip_reason[2], "");
}

TEST(NeedProviders, RunNeedsWaitForTheRunAndForTechniquesThatWillRun) {
  Counted counted;
  Registry plugins;
  plugins.add_provider(counting_provider(&counted, NeedProvider::When::Run));
  Scene s = box_on_ground();
  const TechniqueInfo counting = wanting("counting", {"caster_count"});
  ResolvedNeeds r = resolve_needs(s, {&counting}, &plugins, Derive::Decide);
  EXPECT_EQ(counted.derived, 0);
  ASSERT_FALSE(r.log.empty());
  EXPECT_EQ(r.log.back(), "how many meshes cast (built when run)");
  r = resolve_needs(s, {&counting}, &plugins, Derive::All);
  EXPECT_EQ(counted.derived, 1);

  // A technique skipped for another need gets no Run data.
  s.meshes[0] = make_ground_plane("open caster", glm::vec3(0, 1, 0), 1.0f);
  s.meshes[0].casts_shadow = true;
  const TechniqueInfo closed_and_counting =
      wanting("closed_counting", {plugin::need::kClosedCasters, "caster_count"});
  r = resolve_needs(s, {&closed_and_counting}, &plugins, Derive::All);
  EXPECT_NE(r.skip_reason[0], "");
  EXPECT_EQ(counted.derived, 1);
}

TEST(NeedProviders, ANeedWithoutAProviderSkipsTheTechniqueWithTheName) {
  const Scene s = box_on_ground();
  const TechniqueInfo t = wanting("lost", {"no_such_need"});
  const ResolvedNeeds r = resolve_needs(s, {&t}, nullptr, Derive::All);
  EXPECT_EQ(r.skip_reason[0], "lost needs 'no_such_need', which no loaded plugin provides");
}

TEST(NeedProviders, ReadingANeedAsTheWrongTypeOrUndeclaredIsAnError) {
  DerivedData d;
  d.put<int>("n", std::make_shared<int>(3));
  EXPECT_EQ(d.get<int>("n"), 3);
  try {
    (void)d.get<float>("n");
    FAIL() << "read an int as a float";
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()), "need 'n' holds int, read as float");
  }
  EXPECT_THROW((void)d.get<int>("m"), std::logic_error);
  EXPECT_EQ(d.find<int>("m"), nullptr);
}

TEST(NeedProviders, ARunNeedThatWouldSkipJobsIsRefused) {
  Counted c;
  Registry plugins;
  NeedProvider p = counting_provider(&c, NeedProvider::When::Run);
  p.unmet = [](const Scene&, const DerivedData&) { return std::string("never"); };
  plugins.add_provider(std::move(p));
  const TechniqueInfo t = wanting("counting", {"caster_count"});
  EXPECT_THROW(resolve_needs(box_on_ground(), {&t}, &plugins, Derive::All), std::logic_error);
}

TEST(NeedProviders, TwoProvidersOfOneNeedAreRefused) {
  Counted c;
  Registry plugins;
  plugins.add_provider(counting_provider(&c, NeedProvider::When::Run));
  EXPECT_THROW(plugins.add_provider(counting_provider(&c, NeedProvider::When::Run)),
               std::logic_error);
}

TEST(NeedProviders, APluginCannotReplaceAHarnessNeed) {
  Counted c;
  NeedProvider p = counting_provider(&c, NeedProvider::When::Plan);
  p.name = plugin::need::kPlanarReceiver;
  Registry plugins;
  plugins.add_provider(p);
  try {
    find_need_provider(plugin::need::kPlanarReceiver, &plugins);
    FAIL() << "a plugin replaced the harness's planar_receiver";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'planar_receiver'"), std::string::npos) << e.what();
  }
  // Without the clash, the harness's provider is found as before.
  EXPECT_NE(find_need_provider(plugin::need::kPlanarReceiver, nullptr), nullptr);
}

TEST(SilhouetteEdges, AClosedBoxHasEighteenEdgesEachWithTwoFaces) {
  // 6 faces × 2 triangles: 12 face edges and 6 face diagonals.
  const Mesh box = make_box("box", {0, 1, 0}, {0.5f, 1.0f, 1.5f});
  const auto edges = mesh_edges(box);
  EXPECT_EQ(edges.size(), 18u);
  for (const auto& e : edges) EXPECT_GE(e.right, 0);
}

TEST(SilhouetteEdges, AnOpenQuadHasFourBoundaryEdgesAndOneShared) {
  const Mesh quad = make_ground_plane("quad", glm::vec3(0), 1.0f);
  ASSERT_EQ(quad.triangle_count(), 2u);
  const auto edges = mesh_edges(quad);
  ASSERT_EQ(edges.size(), 5u);
  int boundary = 0;
  for (const auto& e : edges) boundary += e.right < 0 ? 1 : 0;
  EXPECT_EQ(boundary, 4);
}

TEST(SilhouetteEdges, FacePlanesPointOutwardsAndSpanTheirEdges) {
  const Scene s = box_on_ground();
  const auto packed = pack_silhouette_edges(s);
  ASSERT_EQ(packed.mesh_ranges.size(), 2u);
  EXPECT_EQ(packed.mesh_ranges[0], std::make_pair(0, 18));
  EXPECT_EQ(packed.mesh_ranges[1], std::make_pair(18, 0));  // the ground casts nothing
  const glm::vec4 centre(0, 1, 0, 1);
  for (int i = 0; i < 18; ++i) {
    const float* r = &packed.floats[size_t(i) * 16];
    const glm::vec4 p0(r[0], r[1], r[2], 1), p1(r[4], r[5], r[6], 1);
    const glm::vec4 a(r[8], r[9], r[10], r[11]), b(r[12], r[13], r[14], r[15]);
    EXPECT_EQ(r[3], 0.0f);  // mesh index
    EXPECT_EQ(r[7], 1.0f);  // two faces
    for (const glm::vec4& plane : {a, b}) {
      EXPECT_NEAR(glm::length(glm::vec3(plane)), 1.0f, 1e-6f);
      EXPECT_LT(glm::dot(plane, centre), 0.0f);  // the centre is inside
      EXPECT_NEAR(glm::dot(plane, p0), 0.0f, 1e-5f);
      EXPECT_NEAR(glm::dot(plane, p1), 0.0f, 1e-5f);
    }
  }
}

}  // namespace
}  // namespace sb::test
