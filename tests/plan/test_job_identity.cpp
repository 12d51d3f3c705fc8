// A job's identity (run/job_identity.h, the spec a rerun compares) is
// generated from what each setting declares it decides (core::Decides), not
// listed by hand: these tests walk every described setting (each
// config block key, each parameter of each scene type and of each registered
// technique), change it, and check that the spec changes exactly when the
// setting says it decides a number. A new key or parameter is walked without
// a new test. A file parameter is identified by the file's content: another
// path to the same bytes keeps the spec, other bytes change it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/config_blocks.h"
#include "config/experiment.h"
#include "config/identity.h"
#include "core/error.h"
#include "core/scene_types.h"
#include "run/job_identity.h"
#include "test_registry.h"

namespace sb::test {

using config::config_blocks;
using config::Experiment;
using config::parse_experiment;
using core::Decides;
using core::ParamSpec;
using core::ParamType;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A folder of this test process's own, with two files of the same bytes
// under two names and one of other bytes.
struct IdentityFiles {
  fs::path dir;
  IdentityFiles() {
    dir = fs::temp_directory_path() / ("shadowbench_test_identity_" + std::to_string(::getpid()));
    fs::create_directories(dir / "moved");
    std::ofstream(dir / "a.bin") << "the same bytes";
    std::ofstream(dir / "moved" / "renamed.bin") << "the same bytes";
    std::ofstream(dir / "other.bin") << "other bytes";
  }
  ~IdentityFiles() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  IdentityFiles(const IdentityFiles&) = delete;
  IdentityFiles& operator=(const IdentityFiles&) = delete;
  std::string config() const { return (dir / "c.json").string(); }
};

const IdentityFiles& identity_files() {
  static const IdentityFiles files;
  return files;
}

// One scene of `type` and one technique, with the stability block present
// so that its keys are in effect; a scene type's required file parameters
// name a file of the folder.
json identity_config(const std::string& scene_type = "sphere_grid",
                     const std::string& technique = "none") {
  json params = json::object();
  if (const core::SceneType* st = core::find_scene_type(scene_type))
    for (const ParamSpec& s : st->params)
      if (s.is_path) params[s.name] = "a.bin";
  return {{"name", "identity"},
          {"scenes", {{{"type", scene_type}, {"params", params}}}},
          {"techniques", {technique}},
          {"resolutions", {{32, 24}}},
          {"stability", json::object()}};
}

std::optional<Experiment> parsed(const json& config) {
  try {
    return parse_experiment(config, identity_files().config(), registry());
  } catch (const core::InputError&) {
    return std::nullopt;
  }
}

// The spec of the experiment's one job, as a run without options makes it;
// the scene is not built, so files are hashed as they are.
json spec_of(const Experiment& e) {
  const run::RunOptions o;
  const run::EmbreeChoice embree = run::choose_embree(e, o);
  return run::job_spec(e, o, embree, e.scenes.at(0), {}, e.resolutions.at(0), e.techniques.at(0));
}

// Values other than `current` a setting of `spec` accepts, most likely first
// (rules across settings may refuse some). Strings have no generic other
// value: a string key without one here fails the walk, so that whoever adds
// one says what to change it to.
std::vector<json> other_values(const ParamSpec& s, const json& current) {
  std::vector<json> out;
  switch (s.type) {
    case ParamType::Bool:
      out.push_back(!current.get<bool>());
      break;
    case ParamType::Int: {
      const long long v = current.get<long long>();
      for (long long c : {v + 1, v - 1, v * 2, v + 2, static_cast<long long>(s.min),
                          static_cast<long long>(s.max)})
        if (c != v && double(c) >= s.min && double(c) <= s.max) out.push_back(c);
      break;
    }
    case ParamType::Float: {
      const double v = current.get<double>();
      for (double c : {v * 1.5, v * 0.5, v + 1, v == 0 ? 0.5 : v * 0.9, s.min, s.max})
        if (c != v && c >= s.min && c <= s.max) out.push_back(c);
      break;
    }
    case ParamType::Choice:
      for (const std::string& c : s.choices)
        if (current != c) out.push_back(c);
      break;
    case ParamType::String:
      if (s.name == "control") out.push_back(nullptr);  // frames.control off
      if (s.name == "embree_config") out.push_back("isa=sse2");
      break;
  }
  return out;
}

// Changes one setting of `base` (through `set`) to each of its other values
// until a config with it parses, and checks the spec against the
// declaration; false when no other value parses.
bool spec_follows_declaration(const json& base, const std::string& what, const ParamSpec& s,
                              const json& current,
                              const std::function<void(json&, const json&)>& set) {
  const std::optional<Experiment> e = parsed(base);
  EXPECT_TRUE(e) << base.dump();
  if (!e) return true;
  const json before = spec_of(*e);
  for (const json& v : other_values(s, current)) {
    json changed = base;
    set(changed, v);
    const std::optional<Experiment> c = parsed(changed);
    if (!c) continue;
    const json after = spec_of(*c);
    if (s.decides == Decides::None)
      EXPECT_EQ(before, after) << what << " declares it decides no number, yet changing it from "
                               << current.dump() << " to " << v.dump() << " changes the spec";
    else
      EXPECT_NE(run::job_spec_hash(before), run::job_spec_hash(after))
          << what << " decides " << core::to_string(s.decides) << ", yet changing it from "
          << current.dump() << " to " << v.dump() << " leaves the spec as it was";
    return true;
  }
  return false;
}

void expect_spec_follows_declaration(const json& base, const std::string& what, const ParamSpec& s,
                                     const json& current,
                                     const std::function<void(json&, const json&)>& set) {
  if (!spec_follows_declaration(base, what, s, current, set) && !other_values(s, current).empty())
    ADD_FAILURE() << what << ": no other value of it parses (add one to other_values)";
}

TEST(JobIdentity, EveryConfigBlockKeyChangesTheSpecExactlyWhenItDecidesANumber) {
  const json base = identity_config();
  const std::optional<Experiment> e = parsed(base);
  ASSERT_TRUE(e);
  size_t walked = 0;
  for (const config::ConfigBlock& b : config_blocks())
    for (const config::BlockKey& k : b.keys) {
      ++walked;
      expect_spec_follows_declaration(base, b.name + "." + k.spec.name, k.spec, k.value(*e),
                                      [&](json& c, const json& v) { c[b.name][k.spec.name] = v; });
    }
  EXPECT_GE(walked, 20u);  // frames, reference, stability, metrics, limits
}

TEST(JobIdentity, EverySceneEntryKeyChangesTheSpecExactlyWhenItDecidesANumber) {
  const json base = identity_config();
  const std::optional<Experiment> e = parsed(base);
  ASSERT_TRUE(e);
  const json before = spec_of(*e);
  for (const config::SceneEntryKey& k : config::scene_entry_keys()) {
    json changed = base;
    changed["scenes"][0][k.name] = k.example;
    const std::optional<Experiment> c = parsed(changed);
    ASSERT_TRUE(c) << "scene entry key " << k.name << ": its example does not parse";
    if (k.decides == Decides::None)
      EXPECT_EQ(spec_of(*c), before) << "scene entry key " << k.name;
    else
      EXPECT_NE(spec_of(*c), before) << "scene entry key " << k.name;
  }
}

TEST(JobIdentity, EveryScenesParameterChangesTheSpecExactlyWhenItDecidesANumber) {
  for (const core::SceneType& st : core::scene_types()) {
    const json base = identity_config(st.name);
    const std::optional<Experiment> e = parsed(base);
    ASSERT_TRUE(e) << st.name;
    for (const ParamSpec& s : st.params) {
      if (s.is_path) continue;  // below
      expect_spec_follows_declaration(
          base, "scene " + st.name + " parameter " + s.name, s, e->scenes[0].params.json()[s.name],
          [&](json& c, const json& v) { c["scenes"][0]["params"][s.name] = v; });
    }
  }
}

// A technique entry of `t` with `params`.
json technique_entry(const plugin::TechniqueInfo& t, const json& params) {
  return {{"name", t.name}, {"params", params}};
}

TEST(JobIdentity, EveryTechniquesParameterChangesTheSpecExactlyWhenItDecidesANumber) {
  size_t walked = 0;
  for (const plugin::TechniqueInfo& t : registry().all()) {
    const json base = identity_config("sphere_grid", t.name);
    const std::optional<Experiment> e = parsed(base);
    if (!e) continue;  // a technique that needs parameters set (none yet)
    for (const ParamSpec& s : t.params) {
      ++walked;
      const std::string what = "technique " + t.name + " parameter " + s.name;
      const auto set = [&](const json& others) {
        return [&t, &s, others](json& c, const json& v) {
          json params = others;
          params[s.name] = v;
          c["techniques"][0] = technique_entry(t, params);
        };
      };
      const json current = e->techniques[0].params.json()[s.name];
      if (spec_follows_declaration(base, what, s, current, set(json::object()))) continue;
      // A rule across parameters refuses every other value with the others'
      // defaults (shadow_volume's silhouette with GPU silhouettes): walk it
      // from another value of one other parameter.
      bool walked_elsewhere = false;
      for (const ParamSpec& q : t.params) {
        if (q.name == s.name || walked_elsewhere) continue;
        for (const json& w : other_values(q, e->techniques[0].params.json()[q.name])) {
          const json others = {{q.name, w}};
          json from = base;
          from["techniques"][0] = technique_entry(t, others);
          const std::optional<Experiment> f = parsed(from);
          if (!f) continue;
          walked_elsewhere =
              spec_follows_declaration(from, what + " (with " + q.name + " " + w.dump() + ")", s,
                                       f->techniques[0].params.json()[s.name], set(others));
          if (walked_elsewhere) break;
        }
      }
      if (!walked_elsewhere && !other_values(s, current).empty())
        ADD_FAILURE() << what << ": no other value of it parses (add one to other_values)";
    }
  }
  EXPECT_GE(walked, 50u);
}

TEST(JobIdentity, AFileParameterIsIdentifiedByTheFilesContentNotItsPath) {
  for (const core::SceneType& st : core::scene_types())
    for (const ParamSpec& s : st.params) {
      if (!s.is_path) continue;
      const json base = identity_config(st.name);
      const auto with = [&](const std::string& file) {
        json c = base;
        c["scenes"][0]["params"][s.name] = file;
        const std::optional<Experiment> e = parsed(c);
        EXPECT_TRUE(e) << c.dump();
        return e ? spec_of(*e) : json();
      };
      const json spec = with("a.bin");
      EXPECT_EQ(spec["scene"]["params"][s.name]["sha256"],
                "7d95d9eeb9c191ad25da1c2014f6985c9a3094bf5065029ea0a79767f0522ce6")
          << "the SHA-256 of \"the same bytes\" (sha256sum)";
      // Moved and renamed, or named by an absolute path: the same job.
      EXPECT_EQ(with("moved/renamed.bin"), spec) << st.name << "." << s.name;
      EXPECT_EQ(with((identity_files().dir / "a.bin").string()), spec) << st.name << "." << s.name;
      // Other bytes: another job.
      EXPECT_NE(with("other.bin"), spec) << st.name << "." << s.name;
    }
}

TEST(JobIdentity, SettingsThatDecideNoNumberAreLeftOutOfTheSpec) {
  const std::optional<Experiment> e = parsed(identity_config());
  ASSERT_TRUE(e);
  const json spec = spec_of(*e);
  EXPECT_FALSE(spec.contains("limits")) << spec.dump(2);
  EXPECT_FALSE(spec["reference"].contains("cache")) << spec.dump(2);
  // The rest is named fields, as docs/results.md lists them.
  EXPECT_EQ(spec["frames"]["timed"], 10);
  EXPECT_EQ(spec["reference"]["spp"], 256);
  EXPECT_EQ(spec["stability"]["flicker_frames"], 8);
}

}  // namespace
}  // namespace sb::test
