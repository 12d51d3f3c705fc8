#pragma once
// Change points of one performance-history series: the runs, in
// commit order, where a series (scene, resolution, technique variant) moved
// to a new level and stayed there.
//
// Method: PELT (Killick, Fearnhead & Eckley 2012, "Optimal detection of
// changepoints with a linear computational cost") minimises, over every
// segmentation into segments of at least `min_segment` runs,
//     sum over segments of (sum of squared deviations from the segment mean)
//     + penalty * (number of change points),
// exactly (its pruning drops only split points that can never be optimal).
//   - Scale: the relative scale works on log(value), so that a +20 % step is
//     the same size at any level and multiplicative noise (timings) is
//     additive; the absolute scale works on the values (errors that can be 0).
//   - Noise: sigma = MAD of the first differences / (sqrt(2) * 0.6745), robust
//     to the steps themselves (each is one difference out of n - 1), so that
//     unchanged code yields no step at any noise level. Floored at
//     `noise_floor` (relative scale: 0.5 % by default; absolute scale:
//     noise_floor * the median |value|, or * the largest |value| when that
//     median is 0), so that a series flat to the last digit does not turn
//     every later wiggle into a step. A series that is all zeros has no step.
//   - Outliers: a run more than 3 sigma beyond both the median of the
//     min_segment runs before it and that of the min_segment runs after it is
//     clipped to 3 sigma beyond the nearer one (min_segment >= 2), so that one
//     run on a busy machine does not weigh like a level of its own.
//   - Penalty = beta * sigma^2 * log(n), n the number of runs with a value.
//     The MAD of 20 differences is a rough estimate (about +-25 %), and an
//     underestimate lowers the penalty by its square; so, after a first
//     segmentation, sigma is raised to the residual noise around the segments
//     when that is larger (the root mean square deviation from each segment's
//     median, each capped at 3 sigma), and the series segmented again. This
//     only removes steps: false steps at 10 % noise (20 runs, beta 7) went from
//     1.4 % to 0.3 %, at an unchanged detection rate.
//   - Serial correlation: noise that carries from one run into the next (a
//     machine drifting, a busy spell) makes neighbouring differences small
//     while the level wanders, which the MAD of differences reads as quiet.
//     In the same rounds, the lag-1 autocorrelation phi of the residuals
//     (capped, so winsorised; bias-corrected as (n r + 1) / (n - 3)) is
//     estimated, and where it exceeds 1 / sqrt(pairs) (white noise does so in
//     16 % of series), sigma becomes max(residual, sigma_MAD / sqrt(1 - phi))
//     * sqrt((1 + phi) / (1 - phi)): the marginal noise, widened as
//     correlated noise widens a segment mean's spread (phi at most 0.8). Up
//     to 4 rounds, sigma only rising.
//   - Runs' own noise (find_change_points with run_noise): each run's own
//     standard error of its value, as its frames measured it. A run weighs
//     (sigma^2 + typical^2) / (sigma^2 + own^2), at most 1, in the segment
//     cost (typical: the median own noise); one below 1/2 (its own noise
//     beyond sigma: measured on a loaded machine) is a loaded run, and
//     counts as half a run toward min_segment, so that a busy spell of up to
//     2 * min_segment - 1 runs makes no segment of its own.
//   Measured by bench/change_point_grid.cpp (2000 simulated histories of 20
//   runs per row, docs/ci.md "The detector on a busy machine"): false steps
//   at 5 % noise, before these two and after: independent runs 0.1 % and
//   0.1 %; phi 0.3 2.2 % and 1.5 %; phi 0.5 9.8 % and 5.1 %; phi 0.7 29.2 %
//   and 11.8 %; a busy spell (+15 %, own noise 6 % against 1 %) of 2 runs
//   1.4 % and 0.0 %, of 3 runs 9.7 % and 0.1 %. The price: a +10 % step
//   after 15 runs at 3 % noise, 5 runs on, is found at its run in 62 % of
//   histories instead of 67 %.
//   - Reported effect: segments are summarised by their medians (of the input
//     values); while some change point moves the median by less than
//     `min_relative_change` (or, absolute scale, `min_absolute_change`), the
//     smallest such one is dropped and its two segments merged.
//
// Defaults, measured by tests/history/test_change_points.cpp (seeded
// synthetic series, value = level * exp(noise * z), z ~ N(0, 1)), here over
// 5000 series per case (the tests' own 500 and 200 are in its comments):
//   - false steps (any step reported) in noise-only series of 20 runs:
//     1 % noise 0 %, 3 % noise 0.16 %, 10 % noise 0.28 % (beta 6: 0 %, 0.30 %,
//     0.50 %; beta 8: 0 %, 0.06 %, 0.12 %);
//   - a +20 % step after 3 runs, series of 10 to 20 runs: found at run 3 in
//     100 % (2 % noise) and 98.0 % (3 % noise) (beta 6: 98.9 %; beta 8:
//     97.2 %; beta 10: 94.1 %); beta 7 keeps both rates well inside the
//     issue's bounds (at most 1 % false, at least 95 % found);
//   - a +30 % step at any allowed run of 20 runs at 3 % noise: that run and no
//     other in 99.9 %;
//   - min_segment = 3: a step is reported once 3 runs stand at the new level,
//     one run later than with 2, which measured the same on all of the above;
//     but with 2, an excursion of two runs (a busy host for two runs, or a
//     change reverted at the next commit) is two steps (2003 steps in 1000
//     series, against 6 with 3). A single outlier run is no step with either.
//   - A step fewer than min_segment runs from either end of the series cannot
//     be placed there: it is reported at the nearest allowed run or not at all
//     (a +30 % step after 2 runs of 15 at 2 % noise: at run 3 in 86 %).
#include <cstddef>
#include <span>
#include <vector>

namespace sb::history {

enum class Scale {
  kRelative,  // log(value); every value must be > 0 (timings, ratios)
  kAbsolute,  // the values as they are (error metrics, which can be 0)
};

struct ChangePointOptions {
  Scale scale = Scale::kRelative;
  // Fewest runs with a value in a segment (>= 1). A series with fewer than
  // 2 * min_segment such runs has no change point.
  size_t min_segment = 3;
  // Penalty per change point, in units of sigma^2 * log(n) (> 0). BIC's
  // would be 2; with sigma estimated from the series itself, 7 (see above).
  double beta = 7.0;
  // Lowest sigma: relative scale, as a fraction (0.005 = 0.5 %, in log units);
  // absolute scale, as a fraction of the median |value| (see above).
  double noise_floor = 0.005;
  // Smallest |after / before - 1| reported (both scales; a step from 0 is an
  // infinite relative change).
  double min_relative_change = 0.05;
  // Absolute scale only: smallest |after - before| reported, in the series'
  // units (0: any).
  double min_absolute_change = 0.0;
  // Re-estimate sigma for noise that carries from one run into the next
  // (above). false: one round of the residual noise, no correction (the
  // detector before it; kept to measure against).
  bool serial_correlation = true;
};

struct ChangePoint {
  size_t index = 0;            // the first run after the step, in the input's indices
  double before = 0;           // median of the segment before (the input's units)
  double after = 0;            // median of the segment after
  double relative_change = 0;  // after / before - 1 (+-inf when before is 0)
  double step_over_sigma = 0;  // |step| / sigma, both on the working scale (log or not)
  size_t runs_before = 0;      // runs with a value in the segment before
  size_t runs_after = 0;       // and after
};

// The change points of `values` (one per run, in commit order), in order.
// NaN marks a run without a value for this series: it is skipped, and indices
// still count it. Throws std::invalid_argument for an infinite value, a
// value <= 0 on the relative scale, or options out of range.
std::vector<ChangePoint> find_change_points(std::span<const double> values,
                                            const ChangePointOptions& options = {});

// The same, with each run's own noise: the standard error of its value as
// the run itself measured it (relative scale: as a fraction, so in log
// units; absolute scale: in the values' units), NaN where unknown; empty, or
// one per value. Runs noisier than the series weigh less and count as half a
// run toward min_segment (above).
std::vector<ChangePoint> find_change_points(std::span<const double> values,
                                            std::span<const double> run_noise,
                                            const ChangePointOptions& options = {});

// The steps with what the detector saw: its final sigma, the serial
// correlation it corrected for, and which runs it took as loaded.
struct SeriesSegmentation {
  std::vector<ChangePoint> steps;
  double sigma = 0;               // on the working scale (log units on the relative scale)
  double serial_correlation = 0;  // phi corrected for (0: none shown)
  std::vector<bool> loaded;       // one per value: a loaded run (counted as half a run)
};
SeriesSegmentation segment_series(std::span<const double> values, std::span<const double> run_noise,
                                  const ChangePointOptions& options = {});

// The series' noise as the detector estimates it, before the floor: MAD of
// the first differences / (sqrt(2) * 0.6745), on the values given (no NaN).
double noise_sigma(std::span<const double> values);

// PELT alone: the optimal split points of `values` (no NaN) for the cost
// above with this penalty and minimum segment length, as the indices of the
// first value of each segment after the first, ascending.
std::vector<size_t> pelt_mean_shift(std::span<const double> values, double penalty,
                                    size_t min_segment);

// The same over weighted values (weights in (0, 1], one per value): the cost
// of a segment is the weighted sum of squared deviations from its weighted
// mean, and a segment needs min_segment runs, a run of weight below 0.5 (a
// loaded run) counting as half.
std::vector<size_t> pelt_mean_shift(std::span<const double> values, std::span<const double> weights,
                                    double penalty, size_t min_segment);

}  // namespace sb::history
