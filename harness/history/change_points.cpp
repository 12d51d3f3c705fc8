#include "history/change_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sb::history {
namespace {

// How far, in sigmas, a run may stray from both its neighbourhoods before it
// is clipped as an outlier (cp_clip_excursions), and the cap on one run's
// deviation in the residual noise (cp_residual_sigma).
constexpr double kCpClipSigmas = 3.0;
// A run whose weight (cp_run_weights) is below this is a loaded run: its own
// noise is larger than the series' noise between runs.
constexpr double kCpLoadedWeight = 0.5;
// The largest serial correlation corrected for: at 0.8, sigma is raised by
// up to 3 times; beyond it 20 runs say too little to tell drift from steps.
constexpr double kCpMaxCorrelation = 0.8;
constexpr double kCpCorrelationZ = 1.0;

// Median of a copy (the average of the middle two for an even count).
double cp_median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
  return (lower + upper) / 2;
}

// Prefix sums for the segment cost: the weighted sum of squared deviations
// from the weighted mean of values [a, b), in O(1); and for the segments a
// split may make: a segment needs `min_segment` runs, each loaded run
// counting as half (2 * steady + loaded >= 2 * min_segment).
struct CpPrefixSums {
  std::vector<double> w1{0.0}, s1{0.0}, s2{0.0};
  std::vector<size_t> weight2{0};  // 2 per steady run, 1 per loaded run
  CpPrefixSums(std::span<const double> y, std::span<const double> w) {
    w1.reserve(y.size() + 1);
    s1.reserve(y.size() + 1);
    s2.reserve(y.size() + 1);
    weight2.reserve(y.size() + 1);
    for (size_t i = 0; i < y.size(); ++i) {
      w1.push_back(w1.back() + w[i]);
      s1.push_back(s1.back() + w[i] * y[i]);
      s2.push_back(s2.back() + w[i] * y[i] * y[i]);
      weight2.push_back(weight2.back() + (w[i] < kCpLoadedWeight ? 1 : 2));
    }
  }
  double cost(size_t a, size_t b) const {
    const double sum = s1[b] - s1[a];
    const double weight = w1[b] - w1[a];
    if (!(weight > 0)) return 0;
    return std::max(0.0, (s2[b] - s2[a]) - sum * sum / weight);
  }
  bool admissible(size_t a, size_t b, size_t min_segment) const {
    return weight2[b] - weight2[a] >= 2 * min_segment;
  }
};

// Median of y[a, b).
double cp_median_of(std::span<const double> y, size_t a, size_t b) {
  return cp_median(std::vector<double>(y.begin() + static_cast<std::ptrdiff_t>(a),
                                       y.begin() + static_cast<std::ptrdiff_t>(b)));
}

// Each value that lies more than `limit` beyond both the median of the `h`
// values before it and that of the `h` after it (on the same side; at an end,
// the one side there is) is pulled back to `limit` beyond the nearer of the
// two. A value on a level that lasts at least h runs is within `limit` of one
// side's median (noise aside), and so is the first or last run of a step; a
// shorter excursion (an outlier run on a busy machine) is not, and no longer
// weighs on the squared-deviation cost like a level of its own.
std::vector<double> cp_clip_excursions(std::span<const double> y, size_t h, double limit) {
  std::vector<double> out(y.begin(), y.end());
  for (size_t i = 0; i < y.size(); ++i) {
    std::vector<double> sides;
    if (i > 0) sides.push_back(cp_median_of(y, i >= h ? i - h : 0, i));
    if (i + 1 < y.size()) sides.push_back(cp_median_of(y, i + 1, std::min(y.size(), i + 1 + h)));
    if (sides.empty()) continue;
    const double lo = *std::min_element(sides.begin(), sides.end());
    const double hi = *std::max_element(sides.begin(), sides.end());
    if (y[i] > hi + limit) out[i] = hi + limit;
    if (y[i] < lo - limit) out[i] = lo - limit;
  }
  return out;
}

// Each run's deviation from its segment's median (segments start at 0 and
// at each of `bounds`), capped at `cap` so that one outlier weighs as a
// 3-sigma run at most.
std::vector<double> cp_residuals(std::span<const double> y, const std::vector<size_t>& bounds,
                                 double cap) {
  std::vector<size_t> ends(bounds);
  ends.push_back(y.size());
  std::vector<double> r(y.size());
  size_t a = 0;
  for (size_t b : ends) {
    const double level = cp_median_of(y, a, b);
    for (size_t i = a; i < b; ++i) r[i] = std::clamp(y[i] - level, -cap, cap);
    a = b;
  }
  return r;
}

// The noise around the segments: root mean square of the weighted residuals
// over (total weight - segments) degrees of freedom. It uses every run,
// unlike the MAD of differences.
double cp_residual_sigma(std::span<const double> r, std::span<const double> w, size_t segments) {
  double squares = 0, weight = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    squares += w[i] * r[i] * r[i];
    weight += w[i];
  }
  const double dof = weight - static_cast<double>(segments);
  return dof > 0 ? std::sqrt(squares / dof) : 0;  // none left: segments of one run
}

// Lag-1 autocorrelation of the (capped, so winsorised) residuals, over the
// pairs of neighbouring runs in one segment: how much a run's noise carries
// into the next (a busy spell, a machine drifting). 0 when it is negative
// or there is too little to tell; at most kCpMaxCorrelation.
double cp_serial_correlation(std::span<const double> r, const std::vector<size_t>& bounds) {
  double cross = 0, squares = 0;
  size_t pairs = 0;
  for (size_t i = 0; i + 1 < r.size(); ++i) {
    if (std::binary_search(bounds.begin(), bounds.end(), i + 1)) continue;
    cross += r[i] * r[i + 1];
    ++pairs;
  }
  for (double v : r) squares += v * v;
  if (pairs < 4 || !(squares > 0)) return 0;
  // The sample autocorrelation of a short series is biased low by about
  // (1 + 3 phi) / n (Kendall 1954; around fitted segments more): corrected as
  // (n r + 1) / (n - 3), which took false steps at phi = 0.7 from 10 % to 6 %
  // of simulated histories (bench/change_point_grid.cpp).
  // Only a correlation the residuals show is corrected: white noise gives
  // r1 > z / sqrt(pairs) in a share of series that z sets (kCpCorrelationZ),
  // and each such series loses power for nothing.
  const double np = static_cast<double>(pairs);
  const double r1 = cross / squares;
  if (!(r1 > kCpCorrelationZ / std::sqrt(np))) return 0;
  return std::min((np * r1 + 1) / (np - 3), kCpMaxCorrelation);
}

// Each run's weight in the segment cost, from its own noise (the standard
// error of its value, NaN where unknown) against the series' noise between
// runs, sigma: (sigma^2 + typical^2) / (sigma^2 + own^2), at most 1, where
// typical is the median own noise of the series. A run as noisy as the
// others weighs 1; one whose own noise is larger than sigma (measured on a
// loaded machine) weighs less than kCpLoadedWeight, and is a loaded run.
std::vector<double> cp_run_weights(std::span<const double> own, double sigma) {
  std::vector<double> known;
  for (double v : own)
    if (std::isfinite(v)) known.push_back(v);
  std::vector<double> w(own.size(), 1.0);
  if (known.empty()) return w;
  const double typical = cp_median(known);
  for (size_t i = 0; i < own.size(); ++i)
    if (std::isfinite(own[i]))
      w[i] = std::min(1.0, (sigma * sigma + typical * typical) / (sigma * sigma + own[i] * own[i]));
  return w;
}

// PELT over weighted runs; segments must be admissible (CpPrefixSums).
std::vector<size_t> cp_pelt(std::span<const double> y, std::span<const double> w, double penalty,
                            size_t min_segment) {
  const size_t n = y.size();
  const size_t m = std::max<size_t>(min_segment, 1);
  const CpPrefixSums sums(y, w);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // best[t]: the least cost of values [0, t); last[t]: its last split point.
  std::vector<double> best(n + 1, kInf);
  std::vector<size_t> last(n + 1, 0);
  best[0] = -penalty;
  // Candidates for the last split point, with the step from which each may be
  // pruned. Killick et al.'s pruning: once best[tau] + cost(tau, t) >= best[t],
  // tau is never the last split point of [0, T) for any T at which [t, T) is
  // a segment (there t itself is a candidate, and cost(tau, t) + cost(t, T)
  // <= cost(tau, T)); before that, tau stays.
  struct Candidate {
    size_t tau;
    size_t prune_from;
  };
  constexpr size_t kNever = std::numeric_limits<size_t>::max();
  std::vector<Candidate> candidates{{0, kNever}};
  auto first_admissible_end = [&](size_t t) {
    size_t end = t + 1;
    while (end <= n && !sums.admissible(t, end, m)) ++end;
    return end;  // n + 1: none
  };
  for (size_t t = 1; t <= n; ++t) {
    std::erase_if(candidates, [t](const Candidate& c) { return c.prune_from <= t; });
    for (const Candidate& c : candidates) {
      if (!sums.admissible(c.tau, t, m)) continue;
      const double f = best[c.tau] + sums.cost(c.tau, t) + penalty;
      if (f < best[t]) {
        best[t] = f;
        last[t] = c.tau;
      }
    }
    if (best[t] == kInf) continue;
    for (Candidate& c : candidates)
      if (c.prune_from == kNever && best[c.tau] + sums.cost(c.tau, t) >= best[t])
        c.prune_from = first_admissible_end(t);
    // t may end the first segments of later [0, T), if [0, t) can be segmented.
    if (t < n) candidates.push_back({t, kNever});
  }
  if (best[n] == kInf) return {};
  std::vector<size_t> splits;
  for (size_t t = last[n]; t > 0; t = last[t]) splits.push_back(t);
  std::reverse(splits.begin(), splits.end());
  return splits;
}

void cp_check_options(const ChangePointOptions& o) {
  if (o.min_segment < 1) throw std::invalid_argument("change points: min_segment must be >= 1");
  if (!(o.beta > 0) || !std::isfinite(o.beta))
    throw std::invalid_argument("change points: beta must be > 0");
  if (!(o.noise_floor > 0) || !std::isfinite(o.noise_floor))
    throw std::invalid_argument("change points: noise_floor must be > 0");
  if (!(o.min_relative_change >= 0) || !(o.min_absolute_change >= 0))
    throw std::invalid_argument("change points: minimum changes must be >= 0");
}

}  // namespace

double noise_sigma(std::span<const double> values) {
  if (values.size() < 2) return 0;
  std::vector<double> d;
  d.reserve(values.size() - 1);
  for (size_t i = 1; i < values.size(); ++i) d.push_back(values[i] - values[i - 1]);
  const double centre = cp_median(d);
  for (double& v : d) v = std::abs(v - centre);
  return cp_median(std::move(d)) / (std::sqrt(2.0) * 0.6745);
}

std::vector<size_t> pelt_mean_shift(std::span<const double> values, double penalty,
                                    size_t min_segment) {
  const std::vector<double> unit(values.size(), 1.0);
  return cp_pelt(values, unit, penalty, min_segment);
}

std::vector<size_t> pelt_mean_shift(std::span<const double> values, std::span<const double> weights,
                                    double penalty, size_t min_segment) {
  if (weights.size() != values.size())
    throw std::invalid_argument("change points: one weight per value");
  for (double w : weights)
    if (!(w > 0 && w <= 1)) throw std::invalid_argument("change points: weights must be in (0, 1]");
  return cp_pelt(values, weights, penalty, min_segment);
}

std::vector<ChangePoint> find_change_points(std::span<const double> values,
                                            const ChangePointOptions& options) {
  return find_change_points(values, {}, options);
}

std::vector<ChangePoint> find_change_points(std::span<const double> values,
                                            std::span<const double> run_noise,
                                            const ChangePointOptions& options) {
  return segment_series(values, run_noise, options).steps;
}

SeriesSegmentation segment_series(std::span<const double> values, std::span<const double> run_noise,
                                  const ChangePointOptions& options) {
  cp_check_options(options);
  SeriesSegmentation detail;
  detail.loaded.assign(values.size(), false);
  if (!run_noise.empty() && run_noise.size() != values.size())
    throw std::invalid_argument("change points: run_noise must have one entry per value");
  const bool relative = options.scale == Scale::kRelative;
  // The runs with a value: their input indices, values, working values and
  // own noise (NaN: unknown).
  std::vector<size_t> index;
  std::vector<double> raw, y, own;
  for (size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isnan(v)) continue;
    if (std::isinf(v))
      throw std::invalid_argument("change points: infinite value at run " + std::to_string(i));
    if (relative && !(v > 0))
      throw std::invalid_argument("change points: value <= 0 at run " + std::to_string(i) +
                                  " on the relative scale");
    index.push_back(i);
    raw.push_back(v);
    y.push_back(relative ? std::log(v) : v);
    const double o = run_noise.empty() ? std::nan("") : run_noise[i];
    own.push_back(std::isfinite(o) && o >= 0 ? o : std::nan(""));
  }
  const size_t n = y.size();
  const size_t m = options.min_segment;
  if (n < 2 * m) return detail;

  double floor = options.noise_floor;
  if (!relative) {
    std::vector<double> magnitude(raw.size());
    std::transform(raw.begin(), raw.end(), magnitude.begin(), [](double v) { return std::abs(v); });
    const double typical = cp_median(magnitude);
    const double level =
        typical > 0 ? typical : *std::max_element(magnitude.begin(), magnitude.end());
    if (level == 0) return detail;  // all zero: nothing moved
    floor = options.noise_floor * level;
  }
  // Centred, so that the prefix sums of squares do not lose the digits that
  // matter to a large constant level (absolute scale).
  const double centre = cp_median(y);
  std::vector<double> centred(y.size());
  std::transform(y.begin(), y.end(), centred.begin(), [centre](double v) { return v - centre; });
  const double mad_sigma = std::max(noise_sigma(y), floor);
  const double limit = kCpClipSigmas * mad_sigma;
  if (m > 1) centred = cp_clip_excursions(centred, m, limit);  // 1: every run may be a level
  const double log_n = std::log(static_cast<double>(n));
  double sigma = mad_sigma;
  std::vector<double> weights = cp_run_weights(own, sigma);
  std::vector<size_t> bounds = cp_pelt(centred, weights, options.beta * sigma * sigma * log_n, m);
  // The MAD of a few differences is a rough estimate (about +-25 % for 20
  // runs), an underestimate lowers the penalty by its square, and noise that
  // carries from one run into the next (serial correlation phi) makes
  // neighbouring differences small while levels wander. So, while steps are
  // found, sigma is re-estimated around them: the residual noise (every run)
  // or the MAD's estimate corrected for phi, sigma_d / sqrt(1 - phi),
  // whichever is larger, times sqrt((1 + phi) / (1 - phi)), the factor by
  // which correlated noise widens a segment mean's spread. Sigma only rises,
  // so steps are only removed; a few rounds reach the fixed point.
  const int rounds = options.serial_correlation ? 4 : 1;  // 1: the detector without it
  for (int round = 0; round < rounds && !bounds.empty(); ++round) {
    const std::vector<double> r = cp_residuals(centred, bounds, limit);
    const double phi = options.serial_correlation ? cp_serial_correlation(r, bounds) : 0.0;
    detail.serial_correlation = std::max(detail.serial_correlation, phi);
    const double marginal =
        std::max(cp_residual_sigma(r, weights, bounds.size() + 1), mad_sigma / std::sqrt(1 - phi));
    const double raised = marginal * std::sqrt((1 + phi) / (1 - phi));
    if (!(raised > sigma * (1 + 1e-9))) break;
    sigma = raised;
    weights = cp_run_weights(own, sigma);
    bounds = cp_pelt(centred, weights, options.beta * sigma * sigma * log_n, m);
  }

  // Segments [starts[k], starts[k + 1]) over the runs with a value; drop the
  // change point of smallest effect while any is below the minimum effect.
  auto below_minimum = [&](double before, double after) {
    const double rel = before == 0 ? (after == 0 ? 0.0 : std::numeric_limits<double>::infinity())
                                   : std::abs(after / before - 1);
    if (rel < options.min_relative_change) return true;
    return !relative && std::abs(after - before) < options.min_absolute_change;
  };
  // Every segment's first run, and n after the last.
  const auto segment_starts = [&] {
    std::vector<size_t> starts{0};
    starts.insert(starts.end(), bounds.begin(), bounds.end());
    starts.push_back(n);
    return starts;
  };
  for (;;) {
    const std::vector<size_t> starts = segment_starts();
    size_t weakest = bounds.size();
    double weakest_step = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < bounds.size(); ++k) {
      const double before = cp_median_of(raw, starts[k], starts[k + 1]);
      const double after = cp_median_of(raw, starts[k + 1], starts[k + 2]);
      if (!below_minimum(before, after)) continue;
      const double step = std::abs(cp_median_of(y, starts[k + 1], starts[k + 2]) -
                                   cp_median_of(y, starts[k], starts[k + 1]));
      if (step < weakest_step) {
        weakest_step = step;
        weakest = k;
      }
    }
    if (weakest == bounds.size()) break;
    bounds.erase(bounds.begin() + static_cast<std::ptrdiff_t>(weakest));
  }

  std::vector<ChangePoint> out;
  const std::vector<size_t> starts = segment_starts();
  for (size_t k = 0; k < bounds.size(); ++k) {
    ChangePoint c;
    c.index = index[starts[k + 1]];
    c.before = cp_median_of(raw, starts[k], starts[k + 1]);
    c.after = cp_median_of(raw, starts[k + 1], starts[k + 2]);
    if (c.before != 0)
      c.relative_change = c.after / c.before - 1;
    else if (c.after != 0)
      c.relative_change = std::copysign(std::numeric_limits<double>::infinity(), c.after);
    c.step_over_sigma = std::abs(cp_median_of(y, starts[k + 1], starts[k + 2]) -
                                 cp_median_of(y, starts[k], starts[k + 1])) /
                        sigma;
    c.runs_before = starts[k + 1] - starts[k];
    c.runs_after = starts[k + 2] - starts[k + 1];
    out.push_back(c);
  }
  detail.steps = std::move(out);
  detail.sigma = sigma;
  for (size_t i = 0; i < n; ++i) detail.loaded[index[i]] = weights[i] < kCpLoadedWeight;
  return detail;
}

}  // namespace sb::history
