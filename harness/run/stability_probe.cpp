#include "run/stability_probe.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/scene_types.h"

namespace sb::run {

using config::StabilityConfig;
using config::TechniqueVariant;
using core::AreaLight;
using core::Bounds;
using core::ImageF;
using core::Params;
using core::ParamSpec;
using core::ParamType;
using core::Scene;
using plugin::FrameInputs;
using plugin::Technique;
using record::FlickerRecord;
using record::SensitivityRecord;
using record::StabilityRecord;

StabilityProbe::StabilityProbe(const StabilityConfig& config, double max_rmse, const Scene& scene,
                               const FrameInputs& in, std::vector<uint8_t> measured,
                               RenderVisibility render, ReferenceVisibility reference,
                               int history_frames)
    : config_(config),
      max_rmse_(max_rmse),
      moved_(scene),
      light_(scene.light),
      in_(in),
      measured_(std::move(measured)),
      render_(std::move(render)),
      reference_(std::move(reference)),
      history_frames_(history_frames) {
  in_.scene = &moved_;
  // The casters' extent, which the maps are fitted to (a ground plane's
  // would make the step depend on how far the ground reaches).
  const Bounds b = scene.caster_bounds();
  step_ = float(config_.flicker_step * (b.empty() ? 1.0 : 2.0 * double(b.radius())));
}

AreaLight StabilityProbe::translated(const AreaLight& light, float distance) {
  // The sun's place moves as a local light's would: the sun turns by
  // atan(distance / its place's distance) about its disk's v axis.
  if (light.is_sun()) {
    const float len = glm::length(light.half_u);
    const glm::vec3 u = len > 0.0f ? light.half_u / len : glm::vec3(1.0f, 0.0f, 0.0f);
    const float away = glm::length(light.center - light.target);
    return core::make_sun_light(light.center + distance * u - light.target, light.target,
                                light.angular_diameter, away, light.intensity);
  }
  AreaLight out = light;
  const float len = glm::length(light.half_u);
  const glm::vec3 u = len > 0.0f ? light.half_u / len : glm::vec3(1.0f, 0.0f, 0.0f);
  out.center += distance * u;
  out.target += distance * u;
  return out;
}

AreaLight StabilityProbe::scaled(const AreaLight& light, float factor) {
  AreaLight out = light;
  out.half_u *= factor;
  out.half_v *= factor;
  // The sun's disk, seen at its place's distance, grows alike.
  if (light.is_sun())
    out.angular_diameter = 2.0f * std::atan(factor * std::tan(0.5f * light.angular_diameter));
  return out;
}

std::pair<double, double> StabilityProbe::points(double value, double lo, double hi) const {
  const double h = config_.sensitivity_step * (value != 0.0 ? std::fabs(value) : 1.0);
  double minus = value - h, plus = value + h;
  if (minus < lo) minus = value;  // one-sided at a bound
  if (plus > hi) plus = value;
  return {minus, plus};
}

double StabilityProbe::measured_rmse(const ImageF& a, const ImageF& b,
                                     const std::vector<uint8_t>& measured) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    if (measured[i] == 0) continue;
    const double d =
        double(a.data[i * size_t(a.channels)]) - double(b.data[i * size_t(b.channels)]);
    if (!std::isfinite(d)) continue;
    sum += d * d;
    ++n;
  }
  return n == 0 ? 0.0 : std::sqrt(sum / double(n));
}

bool StabilityProbe::is_stiff(double relative, double reference_relative) const {
  return relative > config_.stiff_threshold + reference_relative;
}

FlickerRecord StabilityProbe::flicker(Technique& prepared) {
  const int k = config_.flicker_frames;
  if (!reference_flicker_) {
    std::vector<ImageF> refs;
    for (int i = 0; i < k; ++i) {
      moved_.light = translated(light_, float(i) * step_);
      refs.push_back(reference_(moved_));
    }
    moved_.light = light_;
    reference_flicker_ = metrics::flicker(refs, &measured_);
    reference_first_ = refs.front();
    reference_last_ = refs.back();
  }
  std::vector<ImageF> frames;
  for (int i = 0; i < k; ++i) {
    moved_.light = translated(light_, float(i) * step_);
    frames.push_back(render_(prepared, in_));
  }
  moved_.light = light_;
  const metrics::FlickerStats f = metrics::flicker(frames, &measured_);
  FlickerRecord r;
  r.frames = k;
  r.step = step_;
  r.mean = f.mean;
  r.p99 = f.p99;
  r.max = f.max;
  r.frac_over_005 = f.frac_over_005;
  r.nonfinite = std::int64_t(f.nonfinite);
  r.rmse_first = measured_rmse(frames.front(), reference_first_, measured_);
  r.rmse_last = measured_rmse(frames.back(), reference_last_, measured_);
  r.reference_mean = reference_flicker_->mean;
  r.reference_p99 = reference_flicker_->p99;
  r.reference_max = reference_flicker_->max;
  r.reference_frac_over_005 = reference_flicker_->frac_over_005;
  return r;
}

SensitivityRecord StabilityProbe::parameter(const TechniqueVariant& tv, const ParamSpec& spec,
                                            double value) {
  SensitivityRecord r;
  r.value = value;
  const auto [minus, plus] = points(value, spec.min, spec.max);
  const auto render_at = [&](double v) {
    nlohmann::json params = tv.params.json();
    params[spec.name] = v;
    std::unique_ptr<Technique> t = tv.info->create(Params(params));
    t->prepare(in_);
    for (int k = 1; tv.info->temporal && k < history_frames_; ++k) (void)render_(*t, in_);
    return render_(*t, in_);
  };
  try {
    const ImageF lo = render_at(minus), hi = render_at(plus);
    const metrics::Sensitivity s =
        metrics::sensitivity(hi, lo, value, 0.5 * (plus - minus), &measured_);
    r.step = s.step;
    r.dv_dp = s.dv_dp;
    r.relative = s.relative;
    r.stiff = is_stiff(r.relative);
  } catch (const std::exception& ex) {
    r.error = ex.what();
  }
  return r;
}

SensitivityRecord StabilityProbe::light_size(Technique& prepared) {
  SensitivityRecord r;
  const double size = double(std::max(light_.width(), light_.height()));
  r.value = size;
  const double h = config_.sensitivity_step;  // relative: the rectangle scales by 1 ± h
  if (!reference_light_size_) {
    moved_.light = scaled(light_, float(1.0 + h));
    ImageF plus = reference_(moved_);
    moved_.light = scaled(light_, float(1.0 - h));
    ImageF minus = reference_(moved_);
    reference_light_size_.emplace(std::move(plus), std::move(minus));
  }
  moved_.light = scaled(light_, float(1.0 + h));
  const ImageF plus = render_(prepared, in_);
  moved_.light = scaled(light_, float(1.0 - h));
  const ImageF minus = render_(prepared, in_);
  moved_.light = light_;
  const metrics::Sensitivity s = metrics::sensitivity(plus, minus, size, h * size, &measured_);
  const metrics::Sensitivity ref = metrics::sensitivity(
      reference_light_size_->first, reference_light_size_->second, size, h * size, &measured_);
  r.step = s.step;
  r.dv_dp = s.dv_dp;
  r.relative = s.relative;
  r.reference_relative = ref.relative;
  r.stiff = is_stiff(r.relative, ref.relative);
  return r;
}

namespace {

// A switch parameter's value (ParamSpec::enabled_by): true, or a choice other
// than "none".
bool feature_on(const nlohmann::json& value) {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_string()) return value.get<std::string>() != "none";
  return true;
}

}  // namespace

StabilityRecord StabilityProbe::measure(const TechniqueVariant& tv, Technique& prepared) {
  StabilityRecord r;
  r.max_rmse = max_rmse_;
  r.flicker_factor = config_.flicker_factor;
  r.stiff_threshold = config_.stiff_threshold;
  if (config_.flicker_frames >= 2) r.flicker = flicker(prepared);
  if (!config_.sensitivity) return r;
  for (const ParamSpec& spec : tv.info->params) {
    if (spec.type != ParamType::Float) continue;
    const double value = tv.params.json().at(spec.name).get<double>();
    if (spec.sentinel && value == *spec.sentinel) continue;
    // Off, its feature makes the variants equal: a sensitivity of 0 that says nothing.
    if (!spec.enabled_by.empty() && !feature_on(tv.params.json().at(spec.enabled_by))) continue;
    r.sensitivity[spec.name] = parameter(tv, spec, value);
  }
  if (light_.width() > 0.0f && light_.height() > 0.0f)
    r.sensitivity["light_size"] = light_size(prepared);
  return r;
}

}  // namespace sb::run
