#pragma once
// A job's stability figures (config "stability", docs/stability.md), from
// untimed frames rendered after its timed ones:
//  - flicker: the prepared technique under a light translated by a
//    sub-texel step per frame, pooled |ΔV| between consecutive frames,
//    beside the reference's change for the same motion;
//  - sensitivity: for every continuous parameter (ParamType::Float, not at
//    its sentinel, its feature on: ParamSpec::enabled_by), a variant at
//    p + h and one at p - h, prepared and
//    rendered like the job; and for the light's size, the prepared
//    technique under a light scaled by 1 ± h, beside the reference's change.
// One probe per (scene, resolution): the references of the moved lights are
// traced once, on the first job that needs them, and kept for the rest.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/experiment.h"
#include "core/image.h"
#include "core/scene.h"
#include "metrics/stability.h"
#include "plugin/technique.h"
#include "record/stability_record.h"

namespace sb::run {

class StabilityProbe {
 public:
  // One untimed frame of a prepared technique under `in` (whose scene may be
  // the probe's moved copy); returns its V with the attached shadow applied.
  using RenderVisibility =
      std::function<core::ImageF(plugin::Technique&, const plugin::FrameInputs&)>;
  // The reference's V of `scene` (another light) at the job's points, the
  // attached shadow applied.
  using ReferenceVisibility = std::function<core::ImageF(const core::Scene&)>;

  // `history_frames`: the frames a temporal technique's variant renders
  // before its V is read (frames.history), as the job's did.
  StabilityProbe(const config::StabilityConfig& config, double max_rmse, const core::Scene& scene,
                 const plugin::FrameInputs& in, std::vector<uint8_t> measured,
                 RenderVisibility render, ReferenceVisibility reference, int history_frames = 1);

  // `prepared` has rendered the job's frames under the scene's light.
  record::StabilityRecord measure(const config::TechniqueVariant& tv, plugin::Technique& prepared);

  // The light translated by `distance` along its own u axis.
  static core::AreaLight translated(const core::AreaLight& light, float distance);
  // The light's rectangle scaled by `factor` about its centre.
  static core::AreaLight scaled(const core::AreaLight& light, float factor);

 private:
  record::FlickerRecord flicker(plugin::Technique& prepared);
  record::SensitivityRecord parameter(const config::TechniqueVariant& tv,
                                      const core::ParamSpec& spec, double value);
  record::SensitivityRecord light_size(plugin::Technique& prepared);
  // The step h for a value p: sensitivity_step × |p| (× 1 at 0), and the two
  // points it is taken at, kept inside [lo, hi] (one-sided at a bound).
  std::pair<double, double> points(double value, double lo, double hi) const;
  bool is_stiff(double relative, double reference_relative = 0.0) const;
  // RMSE of a's first channel against b's over the `measured` pixels (finite
  // differences only).
  static double measured_rmse(const core::ImageF& a, const core::ImageF& b,
                              const std::vector<uint8_t>& measured);

  config::StabilityConfig config_;
  double max_rmse_;
  core::Scene moved_;  // the scene, its light moved by the probe
  core::AreaLight light_;
  plugin::FrameInputs in_;  // the job's inputs, with the moved scene
  std::vector<uint8_t> measured_;
  RenderVisibility render_;
  ReferenceVisibility reference_;
  int history_frames_;
  float step_ = 0;  // flicker translation per frame, world units
  std::optional<metrics::FlickerStats> reference_flicker_;
  core::ImageF reference_first_, reference_last_;  // the flicker's first and last lights'
  std::optional<std::pair<core::ImageF, core::ImageF>> reference_light_size_;
};

}  // namespace sb::run
