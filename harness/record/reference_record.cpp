#include "record/reference_record.h"

namespace sb {

nlohmann::json ReferenceRecord::to_json() const {
  nlohmann::json j = {{"method", method},
                      {"spp", spp},
                      {"seed", seed},
                      {"embree_isa", embree_isa},
                      {"embree_config", embree_config},
                      {"mean_std_error", json_number(mean_std_error)},
                      {"penumbra_mean_std_error", json_number(penumbra_mean_std_error)},
                      {"penumbra_rms_std_error", json_number(penumbra_rms_std_error)},
                      {"penumbra_pixels", penumbra_pixels},
                      {"attached_shadow_pixels", attached_shadow_pixels},
                      {"horizon_cut_pixels", horizon_cut_pixels},
                      {"cache_key", cache_key},
                      {"from_cache", from_cache},
                      {"seconds", json_number(seconds)}};
  if (!exact_fallback.empty()) j["exact_fallback"] = exact_fallback;
  if (adaptive)
    j["adaptive"] = {{"pilot_spp", adaptive->pilot_spp},
                     {"target_std_error", json_number(adaptive->target_std_error)},
                     {"mean_spp", json_number(adaptive->mean_spp)},
                     {"max_spp", adaptive->max_spp}};
  if (adaptive && adaptive->unproven_stops)
    j["adaptive"]["unproven_stops"] = *adaptive->unproven_stops;
  if (adaptive && adaptive->stop_bias_bound)
    j["adaptive"]["stop_bias_bound"] = json_number(*adaptive->stop_bias_bound);
  return j;
}

ReferenceRecord ReferenceRecord::from_json(const Fields& f) {
  ReferenceRecord r;
  r.method = f.get<std::string>("method");
  r.exact_fallback = f.find<std::string>("exact_fallback").value_or("");
  r.spp = f.get<int>("spp");
  r.seed = f.get<std::uint64_t>("seed");
  r.embree_isa = f.get<std::string>("embree_isa");
  r.embree_config = f.get<std::string>("embree_config");
  r.mean_std_error = f.get<double>("mean_std_error");
  r.penumbra_mean_std_error = f.get<double>("penumbra_mean_std_error");
  r.penumbra_rms_std_error = f.get<double>("penumbra_rms_std_error");
  r.penumbra_pixels = f.get<std::int64_t>("penumbra_pixels");
  r.attached_shadow_pixels = f.get<std::int64_t>("attached_shadow_pixels");
  r.horizon_cut_pixels = f.get<std::int64_t>("horizon_cut_pixels");
  r.cache_key = f.get<std::string>("cache_key");
  r.from_cache = f.get<bool>("from_cache");
  r.seconds = f.get<double>("seconds");
  if (const auto a = f.find_object("adaptive")) {
    AdaptiveReferenceRecord ar;
    ar.pilot_spp = a->get<int>("pilot_spp");
    ar.target_std_error = a->get<double>("target_std_error");
    ar.mean_spp = a->get<double>("mean_spp");
    ar.max_spp = a->get<int>("max_spp");
    ar.unproven_stops = a->find<std::int64_t>("unproven_stops");
    ar.stop_bias_bound = a->find<double>("stop_bias_bound");
    r.adaptive = ar;
  }
  return r;
}

}  // namespace sb
