// A rerun into the same --out keeps a finished job only when nothing that
// decides its numbers changed, and says which setting did: one test per field of the record's spec
// (run/job_identity.h). Each changes one setting of a tiny finished run and reruns it through the
// CLI. Settings a test cannot change from outside (the build, the reference method's version, a
// backend this machine may lack) are changed in the stored record instead, which is what a record
// of another build holds.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "../common/cli_run.h"
#include "../gltf/gltf_builder.h"
#include "e2e_util.h"
#include "plugin/plugin_identity.h"
#include "reference/reference.h"
#include "run/host_info.h"
#include "run/job_identity.h"

namespace sb::test {

using plugin::kPluginApiVersion;
using run::describe_build;
using run::job_spec_hash;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// One job, as cheap as a job gets: no shadows, 32×24, one timed frame.
json tiny_config() {
  return {{"name", "spec"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
          {"techniques", {"none"}},
          {"resolutions", {{32, 24}}},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}, {"cache", false}}}};
}

json adaptive_config() {
  json c = tiny_config();
  c["reference"].update({{"spp", 64}, {"adaptive", true}, {"pilot_spp", 4}});
  return c;
}

// How a run is started: its config, extra options, an environment prefix.
struct Invocation {
  // Implicit, so that a test writes {config, options}, or {} for the tiny run.
  Invocation(json config_ = tiny_config(), std::string options_ = "", std::string environment_ = "")
      : config(std::move(config_)),
        options(std::move(options_)),
        environment(std::move(environment_)) {}
  json config;
  std::string options;
  std::string environment;
};

CliRun run_into(const fs::path& out, const Invocation& how) {
  const fs::path config = out.string() + ".json";
  std::ofstream(config) << how.config.dump();
  return run_command(how.environment + " " + SHADOWBENCH_EXE + " run '" + config.string() +
                     "' --quiet --no-images --isolation none --out '" + out.string() + "' " +
                     how.options);
}

// A finished run of `how`, made once per test process and copied for each
// test that starts from it.
fs::path finished_run(const Invocation& how) {
  static std::map<std::string, fs::path> made;
  const std::string key = how.config.dump() + "|" + how.options + "|" + how.environment;
  auto it = made.find(key);
  if (it == made.end()) {
    const fs::path dir =
        fs::temp_directory_path() / ("shadowbench_test_spec_base_" + std::to_string(::getpid()) +
                                     "_" + std::to_string(made.size()));
    fs::remove_all(dir);
    const CliRun r = run_into(dir, how);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos) << r.output;
    it = made.emplace(key, dir).first;
  }
  fs::path copy = fresh_test_folder("shadowbench_test_spec_") + "/out";
  fs::copy(it->second, copy, fs::copy_options::recursive);
  return copy;
}

// The single record file of a run folder.
fs::path record_file(const fs::path& run_dir) {
  fs::path found;
  for (const auto& f : fs::directory_iterator(run_dir / "records"))
    if (f.path().extension() == ".json") found = f.path();
  return found;
}

json read_record(const fs::path& run_dir) {
  std::ifstream in(record_file(run_dir));
  return json::parse(in);
}

// Rewrites the stored record as `edit` leaves it, under a hash that is not
// today's (the hash of another spec).
void edit_record(const fs::path& run_dir, const std::function<void(json&)>& edit) {
  json r = read_record(run_dir);
  edit(r);
  r["spec_hash"] = "0123456789abcdef";
  std::ofstream(record_file(run_dir)) << r.dump(2);
}

// Reruns `changed` into a finished run of `base`: the job must run again
// and say why, naming `reason`.
void expect_rerun(const Invocation& base, const Invocation& changed, const std::string& reason) {
  const fs::path out = finished_run(base);
  const CliRun r = run_into(out, changed);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: " + reason), std::string::npos)
      << "expected the reason \"" << reason << "\" in:\n"
      << r.output;
}

void expect_config_rerun(const json& base, const json& changed, const std::string& reason) {
  expect_rerun(Invocation{base}, Invocation{changed}, reason);
}

TEST(ResumeSpec, AnUnchangedRerunResumesAndSaysNothingReran) {
  const fs::path out = finished_run({});
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 0 skipped, 0 failed, 1 resumed;"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("rerun"), std::string::npos) << r.output;
}

TEST(ResumeSpec, TheRecordStoresItsSpecWithTheReferenceMethodVersionAndTheBuild) {
  const json r = read_record(finished_run({}));
  ASSERT_TRUE(r.contains("spec")) << r.dump(2);
  const json& spec = r["spec"];
  reference::Settings settings(16, 1);
  EXPECT_EQ(spec["reference"]["method_id"], reference::method_id(settings));
  EXPECT_EQ(spec["build"]["fingerprint"], describe_build().fingerprint.value());
  EXPECT_EQ(spec["build"]["fingerprint"], r["build"]["fingerprint"]);
  // What resuming compares is the hash of exactly this spec: a record of
  // another method version or build has another hash, as the tests below
  // that edit the stored spec assume.
  EXPECT_EQ(r["spec_hash"], job_spec_hash(spec));
}

TEST(ResumeSpec, TheReferenceMethodReruns) {
  json exact = tiny_config();
  exact["reference"]["method"] = "exact";
  expect_config_rerun(tiny_config(), exact, "reference.method changed (monte_carlo -> exact)");
}

TEST(ResumeSpec, TheReferenceSppReruns) {
  json more = tiny_config();
  more["reference"]["spp"] = 64;
  expect_config_rerun(tiny_config(), more, "reference.spp changed (16 -> 64)");
}

TEST(ResumeSpec, TheReferenceSeedReruns) {
  json other = tiny_config();
  other["reference"]["seed"] = 2;
  expect_config_rerun(tiny_config(), other, "reference.seed changed (1 -> 2)");
}

TEST(ResumeSpec, TheReferenceEmbreeIsaReruns) {
  expect_rerun({tiny_config(), "--embree-config isa=sse2"},
               {tiny_config(), "--embree-config isa=sse4.2"},
               "reference.embree_isa changed (sse2 -> sse4.2)");
}

TEST(ResumeSpec, TheAdaptiveReferenceReruns) {
  json uniform = adaptive_config();
  uniform["reference"]["adaptive"] = false;
  expect_config_rerun(uniform, adaptive_config(), "reference.adaptive changed (false -> true)");
}

TEST(ResumeSpec, TheAdaptivePilotReruns) {
  json pilot = adaptive_config();
  pilot["reference"]["pilot_spp"] = 16;
  expect_config_rerun(adaptive_config(), pilot, "reference.pilot_spp changed (4 -> 16)");
}

TEST(ResumeSpec, TheAdaptiveTargetReruns) {
  json target = adaptive_config();
  target["reference"]["target_std_error"] = 0.05;
  expect_config_rerun(adaptive_config(), target,
                      "reference.target_std_error changed (0.01 -> 0.05)");
}

TEST(ResumeSpec, TheReferenceMethodVersionReruns) {
  // What a record of a build before a bump of kMethodVersion holds.
  const fs::path out = finished_run({});
  edit_record(out, [](json& r) {
    r["spec"]["reference"]["method_id"] = "embree_stratified_packet16/0 on Embree 0";
  });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: reference.method_id changed "
                          "(embree_stratified_packet16/0 on Embree 0 -> " +
                          reference::method_id(reference::Settings(16, 1)) + ")"),
            std::string::npos)
      << r.output;
}

TEST(ResumeSpec, TheTimingSourceReruns) {
  // What a record of a run with forced timestamp brackets holds (RunOptions
  // only: no option of the CLI forces them).
  const fs::path out = finished_run({});
  edit_record(out, [](json& r) { r["spec"]["timing"]["source"] = "gl_timestamp_query"; });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: timing.source changed (gl_timestamp_query -> auto)"),
            std::string::npos)
      << r.output;
}

TEST(ResumeSpec, TheSecondReferenceReruns) {
  json second = tiny_config();
  second["reference"]["second_method"] = "exact";
  expect_config_rerun(tiny_config(), second, "reference.second_method changed (null -> exact)");
}

TEST(ResumeSpec, TheControlReruns) {
  json no_control = tiny_config();
  no_control["frames"]["control"] = nullptr;
  // The control as the spec names it, with its plugin (cut at 80 characters).
  expect_config_rerun(tiny_config(), no_control,
                      "frames.control changed ({\"name\":\"none\",\"params\":{},\"plugin\":{");
}

TEST(ResumeSpec, TheWarmUpFramesRerun) {
  json more = tiny_config();
  more["frames"]["warmup"] = 1;
  expect_config_rerun(tiny_config(), more, "frames.warmup changed (0 -> 1)");
}

TEST(ResumeSpec, TheTimedFramesRerun) {
  json more = tiny_config();
  more["frames"]["timed"] = 2;
  expect_config_rerun(tiny_config(), more, "frames.timed changed (1 -> 2)");
}

TEST(ResumeSpec, ThePassDetailReruns) {
  expect_rerun({}, {tiny_config(), "--pass-timing fine"},
               "timing.pass_detail changed (coarse -> fine)");
}

TEST(ResumeSpec, AnInjectedDelayReruns) {
  expect_rerun({}, {tiny_config(), "", "SHADOWBENCH_INJECT_DELAY=none@1"},
               "timing.injected_delay changed (null -> none@1)");
}

TEST(ResumeSpec, TakingTurnsWithAnotherBuildReruns) {
  // compare-builds runs each build into OUT/base and OUT/new, taking turns
  // every --turn-block timed frames; the same config run alone is timed
  // otherwise.
  const fs::path dir = fresh_test_folder("shadowbench_test_spec_");
  const fs::path config = dir / "c.json";
  std::ofstream(config) << tiny_config().dump();
  const std::string exe = SHADOWBENCH_EXE;
  const CliRun turns =
      run_command(exe + " compare-builds '" + config.string() + "' --base " + exe + " --new " +
                  exe + " --turn-block 2 --no-cache --out '" + (dir / "ab").string() + "'");
  ASSERT_TRUE(fs::exists(dir / "ab" / "base" / "records")) << turns.output;
  const CliRun r = run_command(exe + " run '" + config.string() +
                               "' --quiet --no-images --isolation none --out '" +
                               (dir / "ab" / "base").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: timing.turns changed (every 2 timed frames -> none)"),
            std::string::npos)
      << r.output;
}

TEST(ResumeSpec, TheMetricsSettingsRerun) {
  json thirds = tiny_config();
  thirds["metrics"] = {{"distance_thirds", true}};
  expect_config_rerun(tiny_config(), thirds, "metrics.distance_thirds changed (false -> true)");
}

TEST(ResumeSpec, TheStabilitySettingsRerun) {
  json base = tiny_config();
  base["stability"] = {{"flicker_frames", 2}, {"sensitivity", false}};
  json changed = base;
  changed["stability"]["flicker_frames"] = 3;
  expect_config_rerun(base, changed, "stability.flicker_frames changed (2 -> 3)");
}

TEST(ResumeSpec, TheSceneReruns) {
  json lit = tiny_config();
  lit["scenes"][0]["light"] = {{"size", 2}};
  expect_config_rerun(tiny_config(), lit, "scene.light.size changed (absent -> 2)");
}

TEST(ResumeSpec, TheBackendReruns) {
  // A record timed on EGL, rerun on OSMesa (this machine may have no EGL).
  const fs::path out = finished_run({});
  edit_record(out, [](json& r) { r["spec"]["backend"] = "egl"; });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: backend changed (egl -> osmesa)"), std::string::npos)
      << r.output;
}

TEST(ResumeSpec, AnotherBuildReruns) {
  // A record timed by another build (compiler, flags, version): its
  // timings are not this build's.
  const fs::path out = finished_run({});
  edit_record(out, [](json& r) { r["spec"]["build"]["fingerprint"] = "fedcba9876543210"; });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: build.fingerprint changed (fedcba9876543210 -> " +
                          describe_build().fingerprint.value() + ")"),
            std::string::npos)
      << r.output;
}

// sha256sum's digest of a file of the build tree: another implementation than the harness's.
std::string sha256sum(const fs::path& file) {
  const CliRun r = run_command("sha256sum '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.output.substr(0, 64);
}

TEST(ResumeSpec, TheRecordNamesItsPluginAndTheHarnesssCode) {
  const json r = read_record(finished_run({}));
  const fs::path build = fs::path(SHADOWBENCH_EXE).parent_path();
  const fs::path none_so = build / "plugins" / "none.so";
  const json& plugin = r["technique"]["plugin"];
  EXPECT_EQ(plugin["file"], "none.so");
  EXPECT_EQ(plugin["size"], std::int64_t(fs::file_size(none_so)));
  EXPECT_EQ(plugin["sha256"], sha256sum(none_so));
  EXPECT_EQ(plugin["api_version"], kPluginApiVersion);
  EXPECT_EQ(r["build"]["driver_sha256"], sha256sum(SHADOWBENCH_EXE));
  EXPECT_EQ(r["build"]["core_sha256"], sha256sum(build / "harness" / "libshadowbench_core.so"));
  EXPECT_EQ(r["build"]["plugin_api_sha256"],
            sha256sum(build / "harness" / "libshadowbench_plugin_api.so"));
  // The spec holds what decides the numbers: the plugin's hash and the
  // libraries', not the driver's (it embeds `git describe`).
  const json& spec = r["spec"];
  EXPECT_EQ(spec["technique"]["plugin"]["sha256"], plugin["sha256"]);
  EXPECT_EQ(spec["technique"]["plugin"]["api_version"], kPluginApiVersion);
  EXPECT_EQ(spec["build"]["core_sha256"], r["build"]["core_sha256"]);
  EXPECT_EQ(spec["build"]["plugin_api_sha256"], r["build"]["plugin_api_sha256"]);
  EXPECT_FALSE(spec["build"].contains("driver_sha256"));
}

TEST(ResumeSpec, ARebuiltPluginRerunsNamingIt) {
  // What a record of the plugin before it was rebuilt holds.
  const fs::path out = finished_run({});
  std::string today;
  edit_record(out, [&](json& r) {
    today = r["spec"]["technique"]["plugin"]["sha256"].get<std::string>();
    r["spec"]["technique"]["plugin"]["sha256"] = std::string(64, 'a');
  });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: plugin none.so changed (sha256 aaaaaaaaaaaa.. -> " +
                          today.substr(0, 12) + "..)"),
            std::string::npos)
      << r.output;
}

TEST(ResumeSpec, ARebuiltHarnessReruns) {
  // What a record of a build of other code (same compiler and flags) holds.
  const fs::path out = finished_run({});
  std::string today;
  edit_record(out, [&](json& r) {
    today = r["spec"]["build"]["core_sha256"].get<std::string>();
    r["spec"]["build"]["core_sha256"] = std::string(64, 'c');
  });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: build.core_sha256 changed (cccccccccccc.. -> " +
                          today.substr(0, 12) + "..)"),
            std::string::npos)
      << r.output;
}

// A glTF scene of a ground and four floating casters, as a .gltf and its
// .bin in `dir`; `casters` of them in the scene, the others left out.
std::string save_casters_gltf(const fs::path& dir, const std::string& name, int casters = 4) {
  GltfBuilder b;
  const int ground =
      b.mesh({{"attributes", {{"POSITION", b.positions({-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2})}}},
              {"indices", b.accessor(std::vector<uint16_t>{0, 2, 1, 0, 3, 2}, 5123, "SCALAR", 6)}},
             "ground");
  b.node({{"mesh", ground}});
  for (int i = 0; i < 4; ++i) {
    const float x = -1.2f + 0.8f * float(i);
    const int quad = b.mesh(
        {{"attributes",
          {{"POSITION", b.positions({x - 0.2f, 0.6f, -0.2f, x + 0.2f, 0.6f, -0.2f, x + 0.2f, 0.6f,
                                     0.2f, x - 0.2f, 0.6f, 0.2f})}}},
         {"indices", b.accessor(std::vector<uint16_t>{0, 2, 1, 0, 3, 2}, 5123, "SCALAR", 6)}},
        "caster " + std::to_string(i));
    b.node({{"mesh", quad}}, i < casters);
  }
  fs::create_directories(dir);
  return b.save_gltf((dir / name).string(), name + ".bin");
}

// The tiny run of a labelled glTF entry reading `file` (relative to the
// config's folder, or absolute).
json gltf_config(const std::string& file) {
  json c = tiny_config();
  c["scenes"] = {{{"type", "gltf"}, {"label", "casters"}, {"params", {{"file", file}}}}};
  return c;
}

// Runs `config` (written next to `out`) into `out`.
CliRun run_gltf(const fs::path& out, const json& config) {
  return run_into(out, Invocation{config, "--no-cache"});
}

TEST(ResumeSpec, AGltfFileEditedInPlaceRerunsNamingIt) {
  // Two of four casters removed from the file, under the same name: the
  // issue's stale record (the path was the identity) is run again.
  const fs::path dir = fresh_test_folder("shadowbench_test_spec_");
  const std::string file = save_casters_gltf(dir / "model", "casters.gltf");
  const json config = gltf_config("model/casters.gltf");
  CliRun r = run_gltf(dir / "out", config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_NE(r.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos) << r.output;
  const json before = read_record(dir / "out");
  ASSERT_EQ(before["status"], "ok") << before.dump(2);
  ASSERT_EQ(before["scene"]["caster_triangles"], 8) << before.dump(2);
  // The record's spec holds the file's SHA-256, as sha256sum computes it,
  // and the buffer read through it; not the path. (A record of the path
  // alone resumed after the edit below.)
  const json identity = before["spec"]["scene"]["params"]["file"];
  EXPECT_TRUE(identity.is_object()) << identity.dump();
  const std::string was = identity.is_object() ? identity.value("sha256", "") : "";
  EXPECT_EQ(was, sha256sum(file));
  if (identity.is_object()) {
    EXPECT_EQ(identity["reads"]["casters.gltf.bin"], sha256sum(dir / "model" / "casters.gltf.bin"));
  }
  EXPECT_EQ(before["spec"].dump().find("model/"), std::string::npos) << before["spec"].dump(2);

  save_casters_gltf(dir / "model", "casters.gltf", 2);
  r = run_gltf(dir / "out", config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: file " + (dir / "model" / "casters.gltf").string() +
                          ": content changed (sha256 " + was.substr(0, 12) + ".. -> " +
                          sha256sum(file).substr(0, 12) + "..)"),
            std::string::npos)
      << r.output;
  const json after = read_record(dir / "out");
  EXPECT_EQ(after["scene"]["caster_triangles"], 4) << after.dump(2);
}

TEST(ResumeSpec, AFileAGltfFileReadsEditedInPlaceRerunsNamingIt) {
  const fs::path dir = fresh_test_folder("shadowbench_test_spec_");
  save_casters_gltf(dir / "model", "casters.gltf");
  const json config = gltf_config("model/casters.gltf");
  ASSERT_EQ(run_gltf(dir / "out", config).exit_code, 0);
  // The buffer's bytes changed, the .gltf's not: one vertex of the last
  // caster moves (its last float, a z).
  const fs::path bin = dir / "model" / "casters.gltf.bin";
  std::vector<uint8_t> bytes = read_bytes(bin);
  const float z = 0.3f;
  std::memcpy(bytes.data() + bytes.size() - 12 - sizeof z, &z, sizeof z);
  write_bytes(bin, bytes);
  const CliRun r = run_gltf(dir / "out", config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: file casters.gltf.bin of " +
                          (dir / "model" / "casters.gltf").string() + ": content changed (sha256 "),
            std::string::npos)
      << r.output;
}

TEST(ResumeSpec, AGltfFileMovedRenamedOrNamedByAnAbsolutePathResumes) {
  const fs::path dir = fresh_test_folder("shadowbench_test_spec_");
  save_casters_gltf(dir / "model", "casters.gltf");
  ASSERT_EQ(run_gltf(dir / "out", gltf_config("model/casters.gltf")).exit_code, 0);
  // By an absolute path.
  CliRun r = run_gltf(dir / "out", gltf_config((dir / "model" / "casters.gltf").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 0 skipped, 0 failed, 1 resumed;"), std::string::npos) << r.output;
  // Moved to another folder and renamed (its buffer keeps its name: the
  // .gltf names it).
  fs::create_directories(dir / "elsewhere");
  fs::rename(dir / "model" / "casters.gltf", dir / "elsewhere" / "renamed.gltf");
  fs::rename(dir / "model" / "casters.gltf.bin", dir / "elsewhere" / "casters.gltf.bin");
  r = run_gltf(dir / "out", gltf_config("elsewhere/renamed.gltf"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 0 skipped, 0 failed, 1 resumed;"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("rerun"), std::string::npos) << r.output;
}

TEST(ResumeSpec, ARecordWithoutAStoredSpecRerunsSayingSo) {
  // A record from before records stored their spec: its hash was made by
  // another recipe, and nothing says which settings it had.
  const fs::path out = finished_run({});
  edit_record(out, [](json& r) { r.erase("spec"); });
  const CliRun r = run_into(out, {});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 job rerun: its record stores no spec"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sb::test
