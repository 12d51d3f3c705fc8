#include "run/job_identity.h"

#include <array>
#include <cstdlib>
#include <ctime>

#include "config/identity.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/names.h"
#include "plugin/needs.h"
#include "plugin/registry.h"
#include "reference/embree_isa.h"
#include "reference/reference.h"
#include "run/host_info.h"
#include "run/injected_delay.h"
#include "store/results_store.h"

namespace sb::run {

using config::blocks_identity;
using config::Experiment;
using config::ReferenceConfig;
using config::Resolution;
using config::scene_identity;
using config::SceneVariant;
using config::technique_identity;
using config::TechniqueVariant;
using core::Decides;
using core::Hasher;
using core::InputError;
using core::InputFile;
using core::job_id;
using plan::ScenePlan;
using plugin::PluginIdentity;
using record::BuildRecord;
using record::BuiltScene;
using record::JobRecord;
using record::PluginRecord;
using record::TechniqueRecord;
using store::json_text;

using json = nlohmann::json;

std::string now_iso8601() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

EmbreeChoice choose_embree(const Experiment& e, const RunOptions& o) {
  EmbreeChoice c;
  c.config = !o.embree_config.empty()                      ? o.embree_config
             : !e.reference.settings.embree_config.empty() ? e.reference.settings.embree_config
                                                           : reference::default_embree_config();
  c.isa = reference::resolve_isa(c.config);
  return c;
}

namespace {

std::array<double, 3> vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The module that registered the technique, when one did (a test's own
// registrations have none).
const PluginIdentity* plugin_of(const Experiment& e, const TechniqueVariant& tv) {
  return e.registry == nullptr ? nullptr : e.registry->plugin_of(tv.info->name);
}

// SHADOWBENCH_INJECT_DELAY as set, when it slows this job; else null. A
// malformed value is kept as it is: the executor reports it, not this.
json injected_delay_spec(const TechniqueVariant& tv) {
  const char* value = std::getenv(kInjectDelayVariable);
  if (value == nullptr || *value == '\0') return nullptr;
  try {
    if (!InjectedDelay::parse(value).applies_to(tv.name)) return nullptr;
  } catch (const InputError&) {
  }
  return value;
}

// What a part of the spec that is no config key is computed from.
struct RunContext {
  const Experiment& e;
  const RunOptions& o;
  const EmbreeChoice& embree;
  const TechniqueVariant& tv;
  const BuildRecord& build;
};

// A part of the spec that is no config key: `key` of the spec's member
// `block` ("" for the spec itself), what it decides, and its value.
struct RunPart {
  const char* block;
  const char* key;
  Decides decides;
  json (*value)(const RunContext&);
};

// The one place that lists them: the reference's method with its version
// and the Embree ISA it resolves to, how frames are timed, the backend and
// the build.
const std::vector<RunPart>& run_parts() {
  static const std::vector<RunPart> parts{
      // reference::method_id: the method, its version constants and Embree's
      // version; a bump reruns the jobs it concerns.
      {"reference", "method_id", Decides::Error,
       [](const RunContext& c) -> json {
         const ReferenceConfig& ref = c.e.reference;
         return reference::method_id(reference_settings(ref, c.embree, ref.settings.exact));
       }},
      {"reference", "second_method_id", Decides::Error,
       [](const RunContext& c) -> json {
         const ReferenceConfig& ref = c.e.reference;
         if (!ref.second_exact) return nullptr;
         return reference::method_id(reference_settings(ref, c.embree, *ref.second_exact));
       }},
      {"reference", "embree_isa", Decides::Error,
       [](const RunContext& c) -> json { return c.embree.isa; }},
      {"timing", "pass_detail", Decides::Timing,
       [](const RunContext& c) -> json { return gl::to_string(c.o.pass_detail); }},
      {"timing", "turns", Decides::Timing,
       [](const RunContext& c) -> json {
         return c.o.take_turn ? "every " + std::to_string(c.o.turn_block_frames) + " timed frames"
                              : std::string("none");
       }},
      {"timing", "injected_delay", Decides::Timing,
       [](const RunContext& c) -> json { return injected_delay_spec(c.tv); }},
      // Forced bracket kind, or "auto": the context's (glFinish and CPU
      // clocks on a software rasteriser, GL timestamps on a GPU).
      {"timing", "source", Decides::Timing,
       [](const RunContext& c) -> json {
         return c.o.timing_source ? gl::to_string(*c.o.timing_source) : std::string("auto");
       }},
      {"", "backend", Decides::Both,
       [](const RunContext& c) -> json { return gl::to_string(c.o.backend); }},
      // The toolchain, and the code of the libraries that render and
      // measure. Not the driver's: it embeds `git describe`, which every
      // commit changes, and its own code (the command line) decides no number.
      {"build", "fingerprint", Decides::Both,
       [](const RunContext& c) -> json { return c.build.fingerprint.value_or(""); }},
      {"build", "core_sha256", Decides::Both,
       [](const RunContext& c) -> json { return c.build.core_sha256.value_or(""); }},
      {"build", "plugin_api_sha256", Decides::Both,
       [](const RunContext& c) -> json { return c.build.plugin_api_sha256.value_or(""); }},
  };
  return parts;
}

}  // namespace

reference::Settings reference_settings(const ReferenceConfig& c, const EmbreeChoice& embree,
                                       bool exact) {
  reference::Settings s = c.settings;
  s.embree_config = embree.config;
  s.exact = exact;
  return s;
}

json job_spec(const Experiment& e, const RunOptions& o, const EmbreeChoice& embree,
              const SceneVariant& sv, const std::vector<InputFile>& inputs, const Resolution& res,
              const TechniqueVariant& tv) {
  // The job's own: the scene (its files by content), resolution and technique.
  json spec = {{"scene", scene_identity(sv, inputs)},
               {"resolution", res.label()},
               {"technique", technique_identity(e, tv)}};
  // Every config key that decides a number, as its block declares it.
  spec.update(blocks_identity(e));
  // And what is no config key.
  const BuildRecord build = describe_build();
  const RunContext context{e, o, embree, tv, build};
  for (const RunPart& p : run_parts()) {
    if (p.decides == Decides::None) continue;
    json& where = *p.block == '\0' ? spec : spec[p.block];
    where[p.key] = p.value(context);
  }
  return spec;
}

std::string job_spec_hash(const json& spec) {
  Hasher h;
  h.add(json_text(spec));
  return h.hex();
}

JobRecord identity_record(const Experiment& e, const RunOptions& o, const EmbreeChoice& embree,
                          const SceneVariant& sv, const std::vector<InputFile>& inputs,
                          const Resolution& res, const TechniqueVariant& tv,
                          const std::string& gl_renderer, const std::string& gl_version) {
  JobRecord r;
  r.run_id = o.run_id;
  r.config = e.file;
  r.config_hash = e.content_hash;
  r.experiment = e.name;
  r.job_id = job_id(sv.name, res.label(), tv.name);
  r.spec = job_spec(e, o, embree, sv, inputs, res, tv);
  r.spec_hash = job_spec_hash(*r.spec);
  r.scene_variant = sv.name;
  r.scene.type = sv.type;
  r.scene.variant = sv.name;
  r.scene.params = sv.params.json();
  r.technique_variant = tv.name;
  r.technique = TechniqueRecord{};
  r.technique.name = tv.info->name;
  r.technique.family = tv.info->family;
  r.technique.variant = tv.name;
  r.technique.params = tv.params.json();
  if (tv.info->temporal) r.technique.measured_frame = e.history_frames;
  if (const PluginIdentity* p = plugin_of(e, tv))
    r.technique.plugin = PluginRecord{p->file, p->size, p->sha256, p->api_version};
  r.resolution = res.label();
  r.width = res.width;
  r.height = res.height;
  r.backend = gl::to_string(o.backend);
  r.gl_renderer = gl_renderer;
  r.gl_version = gl_version;
  // The machine and the build, with their fingerprints (run/host_info.h).
  r.host = describe_host(gl_renderer, gl_version, embree.isa);
  r.build = describe_build();
  r.session = o.session;  // the run's (run/session_info.h)
  // Its place in the plan, so that merged shards list jobs as one run would.
  const auto index_of = [](const auto& item, const auto& all) {
    return std::int64_t(&item - all.data());
  };
  r.job_index =
      (index_of(sv, e.scenes) * std::int64_t(e.resolutions.size()) + index_of(res, e.resolutions)) *
          std::int64_t(e.techniques.size()) +
      index_of(tv, e.techniques);
  if (o.shard.count > 1)
    r.shard = std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count);
  return r;
}

BuiltScene built_scene(const SceneVariant& sv, const ScenePlan& st) {
  BuiltScene b;
  b.triangles = static_cast<std::int64_t>(st.scene.triangle_count());
  b.caster_triangles = static_cast<std::int64_t>(st.scene.caster_triangle_count());
  b.analytic_casters = static_cast<std::int64_t>(st.scene.analytic_caster_count());
  const auto& l = st.scene.light;
  b.light = {vec3(l.center), vec3(l.target), {l.width(), l.height()}, l.intensity, std::nullopt};
  if (l.is_sun()) b.light.angular_diameter = glm::degrees(double(l.angular_diameter));
  const auto& c = st.scene.camera;
  b.camera = {vec3(c.eye), vec3(c.target), c.fov_y_degrees};
  b.derived = {st.derived.has(plugin::need::kCasterClosedness),
               st.derived.has(plugin::need::kEdgeAdjacency), sv.infer_receivers,
               st.inferred_receivers};
  return b;
}

}  // namespace sb::run
