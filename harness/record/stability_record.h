#pragma once
// record["stability"]: a job's stability figures and the thresholds the
// stability table judges them by (config "stability", docs/stability.md).
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "record/fields.h"

namespace sb {

// A mean flicker below this is no flicker, whatever the reference's: it
// keeps a technique from being judged against a reference that did not
// move at all (the stability table's rule, results/stability_table.h).
inline constexpr double kFlickerFloor = 1e-4;

// |ΔV| between consecutive frames while the light moves by `step` (world
// units) per frame, beside the reference's own change for the same motion.
struct FlickerRecord {
  int frames = 0;
  double step = 0;
  double mean = 0, p99 = 0, max = 0;
  double frac_over_005 = 0;    // share of |ΔV| over 0.05: "frac_over_0.05"
  std::int64_t nonfinite = 0;  // pixel pairs left out: NaN or infinite V
  double reference_mean = 0, reference_p99 = 0, reference_max = 0, reference_frac_over_005 = 0;

  nlohmann::json to_json() const;
  static FlickerRecord from_json(const Fields& f);
};

// One parameter's central difference at its configured value.
struct SensitivityRecord {
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

  nlohmann::json to_json() const;
  static SensitivityRecord from_json(const Fields& f);
};

struct StabilityRecord {
  double max_rmse = 0, flicker_factor = 0, stiff_threshold = 0;
  std::optional<FlickerRecord> flicker;
  std::map<std::string, SensitivityRecord> sensitivity;  // by parameter ("light_size")

  nlohmann::json to_json() const;
  static StabilityRecord from_json(const Fields& f);
};

}  // namespace sb
