// Every kind of config mistake gives an InputError naming the file, the JSON
// pointer, what was expected and what was found.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "config/experiment.h"
#include "config_fixtures.h"
#include "core/error.h"
#include "plugin/registry.h"

namespace sb {

using config::expand_sweeps;
using config::Experiment;
using config::load_experiment;
using core::InputError;
using plugin::Registry;

namespace {

const Registry& registry() { return test::registry(); }

std::string write_temp(const std::string& name, const std::string& text) {
  return test::write_temp("shadowbench_test_config", name, text);
}

const char* const kValid = R"({
  "name": "t",
  "scenes": [{"type": "sphere_grid", "params": {"grid": 2}}],
  "techniques": ["none", {"name": "pcf_box", "params": {"k": [3, 5], "size": 256}}],
  "resolutions": [[64, 48], "32x24"],
  "frames": {"warmup": 0, "timed": 2},
  "reference": {"spp": 16, "seed": 3}
})";

TEST(Config, ValidConfigExpandsSweeps) {
  const Experiment e = load_experiment(write_temp("valid.json", kValid), registry());
  ASSERT_EQ(e.scenes.size(), 1u);
  ASSERT_EQ(e.techniques.size(), 3u);
  EXPECT_EQ(e.techniques[0].name, "none");
  EXPECT_EQ(e.techniques[1].name, "pcf_box/k=3,size=256");
  EXPECT_EQ(e.techniques[2].name, "pcf_box/k=5,size=256");
  EXPECT_EQ(e.techniques[2].params.get_int("k"), 5);
  EXPECT_EQ(e.techniques[2].params.get_string("filter"), "nearest");  // default filled in
  ASSERT_EQ(e.resolutions.size(), 2u);
  EXPECT_EQ(e.resolutions[1].width, 32);
  EXPECT_EQ(e.resolutions[1].height, 24);
  EXPECT_EQ(e.timed_frames, 2);
  EXPECT_EQ(e.reference.settings.spp, 16);
  EXPECT_EQ(e.reference.settings.seed, 3u);
  EXPECT_FALSE(e.reference.settings.exact);  // Monte Carlo unless the config says "exact"
  EXPECT_EQ(e.content_hash.size(), 16u);
}

// light.type "sun": the direction towards it and its diameter in degrees;
// without a direction, the scene's light's; a sun stays one under an
// override of its intensity, and a size makes it a rectangle again.
TEST(Config, TheSunOverrideMakesTheLightTheSun) {
  const Experiment e = load_experiment(write_temp("sun.json", R"({
    "scenes": [
      {"type": "sphere_grid", "light": {"type": "sun", "direction": [1, 2, 2], "angular_diameter": 1.5}},
      {"type": "sphere_grid", "light": {"type": "sun"}, "label": "default_sun"}
    ],
    "techniques": ["none"], "resolutions": [[8, 8]]})"),
                                       registry());
  ASSERT_EQ(e.scenes.size(), 2u);
  const sb::core::Scene sun = config::build_scene(e.scenes[0], e.file);
  ASSERT_TRUE(sun.light.is_sun());
  EXPECT_NEAR(glm::degrees(sun.light.angular_diameter), 1.5f, 1e-5f);
  EXPECT_NEAR(glm::distance(sun.light.to_sun(), glm::vec3(1, 2, 2) / 3.0f), 0.0f, 1e-6f);
  EXPECT_FALSE(sun.light.is_point());
  EXPECT_FALSE(sun.light.is_segment());

  const sb::core::Scene plain = config::build_scene(e.scenes[1], e.file);
  config::SceneVariant rect_variant = e.scenes[1];
  rect_variant.light = nlohmann::json::object();
  const sb::core::Scene rect = config::build_scene(rect_variant, e.file);
  ASSERT_TRUE(plain.light.is_sun());
  EXPECT_NEAR(glm::degrees(plain.light.angular_diameter), 0.53f, 1e-5f);
  EXPECT_NEAR(glm::distance(plain.light.to_sun(), rect.light.to_sun()), 0.0f, 1e-6f);

  // What a scene generator made the sun: an intensity keeps it one.
  config::SceneVariant brighter = e.scenes[0];
  sb::core::Scene twice = sun;
  brighter.light = {{"intensity", 2.0}};
  sb::config::apply_overrides(brighter, twice);
  EXPECT_TRUE(twice.light.is_sun());
  EXPECT_NEAR(glm::degrees(twice.light.angular_diameter), 1.5f, 1e-5f);
  EXPECT_FLOAT_EQ(twice.light.intensity, 2.0f);
  brighter.light = {{"size", 1.0}};
  sb::core::Scene square = sun;
  sb::config::apply_overrides(brighter, square);
  EXPECT_FALSE(square.light.is_sun());
  EXPECT_FLOAT_EQ(square.light.width(), 1.0f);
}

TEST(Config, ReferenceMethodExactIsRead) {
  std::string text = kValid;
  text.replace(text.find(R"("spp": 16)"), 9, R"("method": "exact", "spp": 16)");
  const Experiment e = load_experiment(write_temp("exact.json", text), registry());
  EXPECT_TRUE(e.reference.settings.exact);
  EXPECT_FALSE(e.reference.second_exact.has_value());  // one reference unless asked
}

TEST(Config, ASecondReferenceMethodIsRead) {
  std::string text = kValid;
  text.replace(text.find(R"("spp": 16)"), 9,
               R"("method": "exact", "second_method": "monte_carlo", "spp": 16)");
  const Experiment e = load_experiment(write_temp("second.json", text), registry());
  EXPECT_TRUE(e.reference.settings.exact);
  ASSERT_TRUE(e.reference.second_exact.has_value());
  EXPECT_FALSE(*e.reference.second_exact);
}

TEST(Config, TheAdaptiveReferenceIsRead) {
  std::string text = kValid;
  text.replace(text.find(R"("spp": 16)"), 9,
               R"("spp": 1024, "adaptive": true, "pilot_spp": 64, "target_std_error": 0.005)");
  const Experiment e = load_experiment(write_temp("adaptive.json", text), registry());
  EXPECT_TRUE(e.reference.settings.adaptive);
  EXPECT_EQ(e.reference.settings.pilot_spp, 64);
  EXPECT_DOUBLE_EQ(e.reference.settings.target_std_error, 0.005);
  const Experiment plain = load_experiment(write_temp("plain.json", kValid), registry());
  EXPECT_FALSE(plain.reference.settings.adaptive);  // off unless asked for
}

TEST(Config, TheStabilityBlockAndACasesThresholdAreRead) {
  std::string text = kValid;
  const std::string reference = R"("reference": {"spp": 16, "seed": 3})";
  text.replace(
      text.find(reference), reference.size(),
      reference + R"(, "stability": {"flicker_frames": 4, "flicker_step": 0, "max_rmse": 0.2})");
  const Experiment e = load_experiment(write_temp("stability.json", text), registry());
  ASSERT_TRUE(e.stability.has_value());
  EXPECT_EQ(e.stability->flicker_frames, 4);
  EXPECT_EQ(e.stability->flicker_step, 0.0);  // a still light
  EXPECT_EQ(e.stability->max_rmse, 0.2);
  EXPECT_TRUE(e.stability->sensitivity);  // defaults for the rest
  EXPECT_EQ(e.stability->flicker_factor, 2.0);
  EXPECT_FALSE(load_experiment(write_temp("plain.json", kValid), registry()).stability);
}

TEST(Config, SweepIsACrossProduct) {
  const auto v = expand_sweeps(
      nlohmann::json::parse(R"({"a": [1, 2, 3], "b": [true, false], "c": 7})"), "f", "/p");
  ASSERT_EQ(v.size(), 6u);
  for (const auto& combo : v) EXPECT_EQ(combo["c"], 7);
  EXPECT_EQ(v[0]["a"], 1);
  EXPECT_EQ(v[0]["b"], true);
  EXPECT_EQ(v[5]["a"], 3);
  EXPECT_EQ(v[5]["b"], false);
}

struct BadCase {
  const char* name;
  const char* json;
  // The place the message must name: a JSON pointer, or a fragment of the
  // message (":1:14: ") where there is none.
  const char* pointer;
  const char* expected;  // a fragment of what was expected/found
};

// One config per kind of mistake.
const BadCase kBadCases[] = {
    {"not_json", "{\"name\": \"x\",, }", ":1:14: ", "invalid JSON"},
    {"top_not_object", "[1, 2]", "/", "expected an experiment (an object), found array"},
    {"unknown_top_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frame": {}})",
     "/frame", "unknown key 'frame'"},
    {"missing_scenes", R"({"techniques": ["none"], "resolutions": [[8, 8]]})", "/",
     "missing required key \"scenes\" in this object"},
    {"unknown_scene",
     R"({"scenes": [{"type": "spheres"}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/type", "unknown scene type \"spheres\" (known: sphere_grid"},
    {"unknown_technique",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none", {"name": "pcss2"}], "resolutions": [[8, 8]]})",
     "/techniques/1/name", "unknown technique \"pcss2\""},
    {"unknown_param",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_box", "params": {"kernel": 3}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/kernel", "unknown parameter 'kernel' (expected one of: k, filter"},
    {"wrong_type",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_box", "params": {"k": "five"}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/k", "parameter 'k': expected an integer, found string \"five\""},
    {"out_of_range",
     R"({"scenes": [{"type": "sphere_grid", "params": {"grid": 0}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/params/grid", "parameter 'grid': expected an integer in [1, 256], found 0"},
    {"even_kernel",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_box", "params": {"k": [3, 4]}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/k/1", "expected an odd integer, found 4"},
    {"early_out_not_fewer_than_taps",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_jitter", "params": {"taps": 16, "early_out_taps": [8, 16]}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/early_out_taps/1",
     "expected fewer early-out taps than taps (16), found 16"},
    {"evsm_three_components",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "evsm", "params": {"components": 3}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/components", "expected 2 or 4, found 3"},
    {"bad_prefilter",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "vsm", "params": {"prefilter": "median"}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/prefilter",
     "expected one of \"none\", \"box\", \"gauss\", found \"median\""},
    {"plates_touching",
     R"({"scenes": [{"type": "plates", "params": {"layout": "stacked", "upper_height": [4, 1]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/params/upper_height/1",
     "expected a number greater than height + thickness (1.05) with layout \"stacked\""},
    {"bad_choice",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "shadow_map", "params": {"cull": "sideways"}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/cull",
     "expected one of \"none\", \"back\", \"front\", found \"sideways\""},
    {"empty_sweep",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_box", "params": {"k": []}}], "resolutions": [[8, 8]]})",
     "/techniques/0/params/k", "expected a non-empty list to sweep"},
    {"bad_resolution",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": ["800by600"]})",
     "/resolutions/0", "expected \"WIDTHxHEIGHT\" or [width, height], found \"800by600\""},
    {"zero_resolution",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[0, 600]]})",
     "/resolutions/0/0", "expected an integer in [1, 16384], found 0"},
    {"bad_frames",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"timed": 0}})",
     "/frames/timed", "expected an integer in [1, 100000], found 0"},
    // Unlike a technique parameter, a config's own integer is not taken as 10.0.
    {"integral_float_frames",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"timed": 10.0}})",
     "/frames/timed", "expected an integer, found number 10.0"},
    {"timed_neither_count_nor_auto",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"timed": "often"}})",
     "/frames/timed", "expected an integer or \"auto\", found string \"often\""},
    {"auto_block_without_auto",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"timed": 10, "auto_block": 5}})",
     "/frames/auto_block", "applies only with \"timed\": \"auto\""},
    {"auto_bound_below_a_block",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"timed": "auto", "auto_block": 20, "auto_max_frames": 10}})",
     "/frames/auto_max_frames", "expected at least auto_block (20), found 10"},
    {"bad_noise_threshold",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"noise_threshold": 5}})",
     "/frames/noise_threshold", "expected a number in [0, 1], found 5"},
    {"swept_control",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"control": {"name": "pcf_box", "params": {"k": [3, 5]}}}})",
     "/frames/control/params", "expected one control variant, found a sweep of 2"},
    {"unknown_control",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "frames": {"control": "nothing"}})",
     "/frames/control", "unknown technique \"nothing\""},
    {"bad_spp",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"spp": 0}})",
     "/reference/spp", "expected an integer in [1, 1048576], found 0"},
    {"adaptive_spp_does_not_nest",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"spp": 100, "adaptive": true}})",
     "/reference/spp",
     "with /reference/adaptive: spp must be the pilot's 4 samples times a power of 4"},
    {"adaptive_bad_pilot",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"spp": 256, "adaptive": true, "pilot_spp": 8}})",
     "/reference/pilot_spp", "the pilot must be 4, 16 or 64 samples, got 8"},
    {"adaptive_bad_target",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"adaptive": true, "target_std_error": 0}})",
     "/reference/target_std_error", "expected a number in"},
    {"bad_embree_config",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"embree_config": "isa=avx9"}})",
     "/reference/embree_config", "Embree device config \"isa=avx9\": unknown ISA \"avx9\""},
    {"bad_reference_method",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"method": "analytic"}})",
     "/reference/method", "expected one of \"monte_carlo\", \"exact\", found \"analytic\""},
    {"bad_second_reference_method",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"second_method": "exact_clipper"}})",
     "/reference/second_method",
     "expected one of \"monte_carlo\", \"exact\", found \"exact_clipper\""},
    {"second_reference_method_is_the_first",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"method": "exact", "second_method": "exact"}})",
     "/reference/second_method",
     "expected the other method than /reference/method (exact), found the same"},
    {"stability_one_flicker_frame",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "stability": {"flicker_frames": 1}})",
     "/stability/flicker_frames", "expected 0 (off) or at least 2 frames, found 1"},
    {"stability_unknown_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "stability": {"flicker": 8}})",
     "/stability/flicker", "unknown key 'flicker'"},
    {"stability_step_too_large",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "stability": {"flicker_step": 0.5}})",
     "/stability/flicker_step", "expected a number in [0, 0.1], found 0.5"},
    {"metrics_distance_thirds_not_bool",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "metrics": {"distance_thirds": 3}})",
     "/metrics/distance_thirds", "expected true or false, found number 3"},
    {"metrics_unknown_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "metrics": {"thirds": true}})",
     "/metrics/thirds", "unknown key 'thirds'"},
    {"limits_not_an_object",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "limits": 30})",
     "/limits", "expected time limits"},
    {"limits_job_seconds_below_a_second",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "limits": {"job_seconds": 0.5}})",
     "/limits/job_seconds", "expected a number in [1, 604800], found 0.5"},
    {"limits_setup_seconds_not_a_number",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "limits": {"setup_seconds": "1h"}})",
     "/limits/setup_seconds", "expected a number, found string"},
    {"limits_unknown_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "limits": {"job_timeout": 5}})",
     "/limits/job_timeout", "unknown key 'job_timeout'"},
    {"scene_max_rmse_out_of_range",
     R"({"scenes": [{"type": "sphere_grid", "max_rmse": 2}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/max_rmse", "expected a number in [0, 1], found 2"},
    {"embree_config_other_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"embree_config": "threads=4"}})",
     "/reference/embree_config", "expected \"isa=NAME\" or \"max_isa=NAME\""},
    {"bad_light",
     R"({"scenes": [{"type": "sphere_grid", "light": {"center": [0, 1]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/center", "expected an array of 3 numbers, found array [0,1]"},
    {"light_target_is_center",
     R"({"scenes": [{"type": "sphere_grid", "light": {"center": [0, 5, 0], "target": [0, 5, 0]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/target", "expected a target different from the light's center"},
    {"light_type_unknown",
     R"({"scenes": [{"type": "sphere_grid", "light": {"type": "spot"}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/type", "expected \"rectangle\" or \"sun\", found string \"spot\""},
    {"sun_with_center",
     R"({"scenes": [{"type": "sphere_grid", "light": {"type": "sun", "center": [0, 5, 0]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/center", "unknown key 'center'"},
    {"sun_without_direction_length",
     R"({"scenes": [{"type": "sphere_grid", "light": {"type": "sun", "direction": [0, 0, 0]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/direction", "expected a non-zero direction towards the sun"},
    {"sun_diameter_out_of_range",
     R"({"scenes": [{"type": "sphere_grid", "light": {"type": "sun", "angular_diameter": 120}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/angular_diameter",
     "expected the sun's angular diameter in degrees in [0.0001, 90], found 120"},
    {"rectangle_with_sun_key",
     R"({"scenes": [{"type": "sphere_grid", "light": {"angular_diameter": 1}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/angular_diameter", "unknown key 'angular_diameter'"},
    {"bad_camera_key",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"fov": 40}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera/fov", "unknown key 'fov'"},
    {"duplicate_variant",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none", "none"], "resolutions": [[8, 8]]})",
     "/techniques/1", "technique variant \"none\" appears twice"},
    // Hostile input: each is bad input (exit 2) with its place, never a crash.
    {"duplicate_key",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"spp": 4, "spp": 8}})",
     "/reference/spp", "the key \"spp\" appears twice"},
    {"number_overflow",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]], "reference": {"seed": 1e400}})",
     ":1:114 (/reference/seed): ", "number overflow parsing '1e400'"},
    {"float_overflow",
     R"({"scenes": [{"type": "sphere_grid", "light": {"intensity": 1e300}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/light/intensity", "expected a number within float range"},
    {"coordinate_out_of_range",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"eye": [0, 3e38, 1]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera/eye/1", "expected a coordinate within ±1e15"},
    {"eye_is_target",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera/target", "camera: eye (1, 2, 3) equals target (1, 2, 3)"},
    {"up_along_view",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 2, 0]}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera", "is parallel to the view direction"},
    {"fov_underflow",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"fov_y": 1e-40}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera/fov_y", "expected degrees in [0.001, 180)"},
    {"near_after_far",
     R"({"scenes": [{"type": "sphere_grid", "camera": {"near": 10, "far": 1}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/camera/far", "expected far greater than near (10), found 1"},
    {"long_label", R"({"scenes": [{"type": "sphere_grid", "label": "LLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLL"}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/label", "expected a label of 1 to 200 bytes, found 201"},
    {"label_with_nul",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "none", "label": "a\u0000b"}], "resolutions": [[8, 8]]})",
     "/techniques/0/label", "expected a label without control characters"},
    {"hidden_run_folder",
     R"({"name": "..x", "scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/name", "not starting with '.'"},
    {"duplicate_resolution",
     R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["none"], "resolutions": [[8, 8], "8x8"]})",
     "/resolutions/1", "resolution 8x8 appears twice"},
    {"too_many_triangles",
     R"({"scenes": [{"type": "sphere_grid", "params": {"grid": 256, "layers": 64, "slices": 1024, "stacks": 1024}}], "techniques": ["none"], "resolutions": [[8, 8]]})",
     "/scenes/0/params/grid", "over the generators' limit of 16777216"},
    {"too_many_jobs",
     R"({"scenes": [{"type": "sphere_grid", "params": {"grid": [1,2,3,4,5,6,7,8,9,10], "layers": [1,2,3,4,5,6,7,8,9,10]}}], "techniques": [{"name": "pcf_box", "params": {"k": [3,5,7,9,11,13,15,17,19,21], "size": [64,128,256,512,1024]}}], "resolutions": [[8, 8], [16, 16], [32, 32]]})",
     "/scenes/0/params",
     "the experiment has 15000 jobs (100 scene variants × 50 technique variants × 3 "
     "resolutions), "
     "over the limit of 10000; raise it with --max-jobs"},
};

class BadConfig : public ::testing::TestWithParam<BadCase> {};

// "file:LINE:COL (/pointer): ": the line and column are checked in
// test_config_positions.cpp.
std::string place(const BadCase& c) {
  return c.pointer[0] == '/' ? "(" + std::string(c.pointer) + "): " : c.pointer;
}

TEST_P(BadConfig, NamesFilePointerAndExpectation) {
  const BadCase& c = GetParam();
  const std::string path = write_temp(std::string(c.name) + ".json", c.json);
  try {
    load_experiment(path, registry());
    FAIL() << c.name << ": no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(place(c)), std::string::npos) << c.name << ": " << what;
    EXPECT_NE(what.find(c.expected), std::string::npos) << c.name << ": " << what;
  }
  // The driver says the same and exits with 2.
  const auto cli = test::run_cli("validate " + path);
  EXPECT_EQ(cli.exit_code, 2) << cli.output;
  EXPECT_NE(cli.output.find(place(c)), std::string::npos) << cli.output;
}

INSTANTIATE_TEST_SUITE_P(Config, BadConfig, ::testing::ValuesIn(kBadCases),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(Config, TheControlIsNoneUnlessTheConfigNamesAnotherOrNull) {
  const std::string base =
      R"({"scenes": [{"type": "sphere_grid"}], "techniques": ["pcf_box"], "resolutions": [[8, 8]])";
  const Experiment by_default =
      load_experiment(write_temp("control_default.json", base + "}"), registry());
  ASSERT_TRUE(by_default.control.has_value());
  EXPECT_EQ(by_default.control->name, "none");
  EXPECT_EQ(by_default.control->info->name, "none");

  const Experiment other = load_experiment(
      write_temp("control_other.json",
                 base + R"(, "frames": {"control": {"name": "pcf_box", "params": {"k": 5}}}})"),
      registry());
  ASSERT_TRUE(other.control.has_value());
  EXPECT_EQ(other.control->name, "pcf_box/k=5");
  EXPECT_EQ(other.control->params.get_int("k"), 5);

  const Experiment off = load_experiment(
      write_temp("control_null.json", base + R"(, "frames": {"control": null}})"), registry());
  EXPECT_FALSE(off.control.has_value());
}

TEST(Config, MissingFileIsAnInputError) {
  EXPECT_THROW(load_experiment("/nonexistent/quick.json", registry()), InputError);
}

TEST(Config, ShippedConfigsAreValid) {
  for (const auto& entry : std::filesystem::directory_iterator(SHADOWBENCH_SOURCE_DIR "/configs")) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(load_experiment(entry.path().string(), registry())) << entry.path();
  }
}

}  // namespace
}  // namespace sb
