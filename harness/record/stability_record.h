#pragma once
// record["stability"]: a job's stability figures and the thresholds the
// stability table judges them by (config "stability", docs/stability.md).
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// A mean flicker below this is no flicker, whatever the reference's: it
// keeps a technique from being judged against a reference that did not
// move at all (the stability table's rule, results/stability_table.h).
inline constexpr double kFlickerFloor = 1e-4;

// |ΔV| between consecutive frames while the light moves by `step` (world
// units) per frame, beside the reference's own change for the same motion.
struct FlickerRecord {
  static constexpr RecordDoc kSchema{
      "FlickerRecord",
      "the per-pixel |ΔV| between consecutive frames over the measured pixels while the light "
      "moves"};

  int frames = 0;
  double step = 0;
  double mean = 0, p99 = 0, max = 0;
  double frac_over_005 = 0;    // share of |ΔV| over 0.05: "frac_over_0.05"
  std::int64_t nonfinite = 0;  // pixel pairs left out: NaN or infinite V
  double reference_mean = 0, reference_p99 = 0, reference_max = 0, reference_frac_over_005 = 0;
  // RMSE of V against the reference of the same light, on the measured
  // pixels, at the first frame (the light not yet moved) and the last: a
  // technique that keeps history lags behind the moving light (ghosting),
  // and its last RMSE grows. Absent from older records.
  std::optional<double> rmse_first, rmse_last;

  template <class V>
  static void describe(V& v) {
    using F = FlickerRecord;
    v.field("frames", &F::frames, {"", "frames rendered"});
    v.field("step", &F::step, {"", "the light's motion per frame, in world units"});
    v.field("mean", &F::mean, {"", "mean |ΔV|"});
    v.field("p99", &F::p99, {"", "99th percentile of |ΔV|"});
    v.field("max", &F::max, {"", "largest |ΔV|"});
    v.field("frac_over_0.05", &F::frac_over_005, {"", "share of |ΔV| over 0.05"});
    v.field("nonfinite", &F::nonfinite, {"", "pixel pairs left out: NaN or infinite V"});
    v.field("rmse_first", &F::rmse_first,
            {"",
             "RMSE of V against the reference of the same light at the first frame, the light "
             "not yet moved; absent from older records"});
    v.field("rmse_last", &F::rmse_last,
            {"",
             "the same at the last frame: above `rmse_first` where a technique's history lags "
             "behind the moving light (ghosting); absent from older records"});
    v.object("reference", {"", "the reference's own change for the same motion"}, [](auto& sub) {
      sub.field("mean", &F::reference_mean, {"", ""});
      sub.field("p99", &F::reference_p99, {"", ""});
      sub.field("max", &F::reference_max, {"", ""});
      sub.field("frac_over_0.05", &F::reference_frac_over_005, {"", ""});
    });
  }
};

// One parameter's central difference at its configured value.
struct SensitivityRecord {
  static constexpr RecordDoc kSchema{"SensitivityRecord",
                                     "one parameter's central difference at its value"};

  double value = 0;
  double step = 0;      // h
  double dv_dp = 0;     // mean of |V(p+h) - V(p-h)| / 2h over the measured pixels
  double relative = 0;  // dv_dp × |p|
  // The reference's relative sensitivity, for a parameter of the scene (the
  // light's size), where part of the change is real.
  std::optional<double> reference_relative;
  bool stiff = false;
  // Why there is no figure: the perturbed variant failed.
  std::optional<std::string> error;

  template <class V>
  static void describe(V& v) {
    using S = SensitivityRecord;
    v.field("value", &S::value, {"", "the parameter's configured value p"});
    v.field("step", &S::step, {"", "h"});
    v.field("dv_dp", &S::dv_dp, {"", "mean |V(p+h) − V(p−h)| / 2h"});
    v.field("relative", &S::relative, {"", "dv_dp·|p|"});
    v.field("reference_relative", &S::reference_relative,
            {"", "the reference's, for the light's size"});
    v.field("stiff", &S::stiff, {"", "over `stiff_threshold`"});
    v.field("error", &S::error, {"", "when a perturbed variant failed"});
  }
};

struct StabilityRecord {
  static constexpr RecordDoc kSchema{
      "StabilityRecord",
      "the job's stability figures and the thresholds its verdict uses "
      "([stability.md](stability.md))"};

  double max_rmse = 0, flicker_factor = 0, stiff_threshold = 0;
  std::optional<FlickerRecord> flicker;
  std::map<std::string, SensitivityRecord> sensitivity;  // by parameter ("light_size")

  template <class V>
  static void describe(V& v) {
    using S = StabilityRecord;
    v.field("max_rmse", &S::max_rmse, {"", "threshold"});
    v.field("flicker_factor", &S::flicker_factor, {"", "threshold"});
    v.field("stiff_threshold", &S::stiff_threshold, {"", "threshold"});
    v.field("flicker", &S::flicker, {"", "the flicker of a moving light"});
    v.field("sensitivity", &S::sensitivity,
            {"",
             "by parameter: every continuous technique parameter not at its sentinel, and "
             "`light_size`",
             Presence::UnlessEmpty});
  }

  nlohmann::json to_json() const;
  static StabilityRecord from_json(const Fields& f);
};

}  // namespace sb::record
