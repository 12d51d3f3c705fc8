#include "run/job_identity.h"

#include <ctime>

#include "core/hash.h"
#include "core/names.h"
#include "reference/embree_isa.h"
#include "results/store.h"
#include "run/host_info.h"

namespace sb {

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
  c.config = !o.embree_config.empty()             ? o.embree_config
             : !e.reference.embree_config.empty() ? e.reference.embree_config
                                                  : reference::default_embree_config();
  c.isa = reference::resolve_isa(c.config);
  return c;
}

std::string job_spec_hash(const Experiment& e, const RunOptions& o, const EmbreeChoice& embree,
                          const SceneVariant& sv, const Resolution& res,
                          const TechniqueVariant& tv) {
  json spec = {{"scene",
                {{"type", sv.type},
                 {"params", sv.params.json()},
                 {"light", sv.light},
                 {"camera", sv.camera},
                 {"infer_receivers", sv.infer_receivers}}},
               {"resolution", res.label()},
               {"technique", {{"name", tv.info->name}, {"params", tv.params.json()}}},
               {"frames", {e.warmup_frames, e.timed_frames}},
               // Monte Carlo's as it always was, so old runs still resume.
               {"reference", e.reference.exact
                                 ? json::array({"exact"})
                                 : json::array({e.reference.spp, e.reference.seed, embree.isa})},
               {"backend", gl::to_string(o.backend)}};
  if (e.stability) spec["stability"] = {e.stability->to_json(), sv.max_rmse.value_or(-1.0)};
  if (e.distance_thirds) spec["distance_thirds"] = true;
  if (e.reference.second_exact)
    spec["second_reference"] = *e.reference.second_exact
                                   ? json::array({"exact"})
                                   : json::array({e.reference.spp, e.reference.seed, embree.isa});
  Hasher h;
  h.add(json_text(spec));
  return h.hex();
}

JobRecord identity_record(const Experiment& e, const RunOptions& o, const EmbreeChoice& embree,
                          const SceneVariant& sv, const Resolution& res, const TechniqueVariant& tv,
                          const std::string& gl_renderer, const std::string& gl_version) {
  JobRecord r;
  r.run_id = o.run_id;
  r.config = e.file;
  r.config_hash = e.content_hash;
  r.experiment = e.name;
  r.job_id = job_id(sv.name, res.label(), tv.name);
  r.spec_hash = job_spec_hash(e, o, embree, sv, res, tv);
  r.scene_variant = sv.name;
  r.scene.type = sv.type;
  r.scene.variant = sv.name;
  r.scene.params = sv.params.json();
  r.technique_variant = tv.name;
  r.technique = {tv.info->name, tv.info->family, tv.name, tv.params.json()};
  r.resolution = res.label();
  r.width = res.width;
  r.height = res.height;
  r.backend = gl::to_string(o.backend);
  r.gl_renderer = gl_renderer;
  r.gl_version = gl_version;
  // The machine and the build, with their fingerprints (run/host_info.h).
  r.host = describe_host(gl_renderer, gl_version, embree.isa);
  r.build = describe_build();
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

}  // namespace sb
