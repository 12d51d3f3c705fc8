#include "record/stability_record.h"

namespace sb {

using json = nlohmann::json;

json FlickerRecord::to_json() const {
  return {{"frames", frames},
          {"step", json_number(step)},
          {"mean", json_number(mean)},
          {"p99", json_number(p99)},
          {"max", json_number(max)},
          {"frac_over_0.05", json_number(frac_over_005)},
          {"nonfinite", nonfinite},
          {"reference",
           {{"mean", json_number(reference_mean)},
            {"p99", json_number(reference_p99)},
            {"max", json_number(reference_max)},
            {"frac_over_0.05", json_number(reference_frac_over_005)}}}};
}

FlickerRecord FlickerRecord::from_json(const Fields& f) {
  FlickerRecord r;
  r.frames = f.get<int>("frames");
  r.step = f.get<double>("step");
  r.mean = f.get<double>("mean");
  r.p99 = f.get<double>("p99");
  r.max = f.get<double>("max");
  r.frac_over_005 = f.get<double>("frac_over_0.05");
  r.nonfinite = f.get<std::int64_t>("nonfinite");
  const Fields ref = f.object("reference");
  r.reference_mean = ref.get<double>("mean");
  r.reference_p99 = ref.get<double>("p99");
  r.reference_max = ref.get<double>("max");
  r.reference_frac_over_005 = ref.get<double>("frac_over_0.05");
  return r;
}

json SensitivityRecord::to_json() const {
  json j = {{"value", json_number(value)},
            {"step", json_number(step)},
            {"dv_dp", json_number(dv_dp)},
            {"relative", json_number(relative)},
            {"stiff", stiff}};
  if (reference_relative) j["reference_relative"] = json_number(*reference_relative);
  if (error) j["error"] = *error;
  return j;
}

SensitivityRecord SensitivityRecord::from_json(const Fields& f) {
  SensitivityRecord r;
  r.value = f.get<double>("value");
  r.step = f.get<double>("step");
  r.dv_dp = f.get<double>("dv_dp");
  r.relative = f.get<double>("relative");
  r.stiff = f.get<bool>("stiff");
  r.reference_relative = f.find<double>("reference_relative");
  r.error = f.find<std::string>("error");
  return r;
}

json StabilityRecord::to_json() const {
  json j = {{"max_rmse", json_number(max_rmse)},
            {"flicker_factor", json_number(flicker_factor)},
            {"stiff_threshold", json_number(stiff_threshold)}};
  if (flicker) j["flicker"] = flicker->to_json();
  if (!sensitivity.empty()) {
    json& s = j["sensitivity"];
    for (const auto& [name, figure] : sensitivity) s[name] = figure.to_json();
  }
  return j;
}

StabilityRecord StabilityRecord::from_json(const Fields& f) {
  StabilityRecord r;
  r.max_rmse = f.get<double>("max_rmse");
  r.flicker_factor = f.get<double>("flicker_factor");
  r.stiff_threshold = f.get<double>("stiff_threshold");
  if (const auto fl = f.find_object("flicker")) r.flicker = FlickerRecord::from_json(*fl);
  if (const auto s = f.find_object("sensitivity"))
    for (const std::string& name : s->keys())
      r.sensitivity[name] = SensitivityRecord::from_json(s->object(name));
  return r;
}

}  // namespace sb
