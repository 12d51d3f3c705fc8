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

// Prefix sums for the segment cost: sum of squared deviations from the mean
// of values [a, b), in O(1).
struct CpPrefixSums {
  std::vector<double> s1{0.0}, s2{0.0};
  explicit CpPrefixSums(std::span<const double> y) {
    s1.reserve(y.size() + 1);
    s2.reserve(y.size() + 1);
    for (double v : y) {
      s1.push_back(s1.back() + v);
      s2.push_back(s2.back() + v * v);
    }
  }
  double cost(size_t a, size_t b) const {
    const double sum = s1[b] - s1[a];
    const double len = static_cast<double>(b - a);
    return std::max(0.0, (s2[b] - s2[a]) - sum * sum / len);
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

// The noise around the segments (starting at 0 and at each of `bounds`):
// root mean square of the deviations from each segment's median, each capped
// at `cap`, over n - segments degrees of freedom. It uses every run, unlike
// the MAD of differences, and the cap keeps one outlier from inflating it.
double cp_residual_sigma(std::span<const double> y, const std::vector<size_t>& bounds, double cap) {
  std::vector<size_t> ends(bounds);
  ends.push_back(y.size());
  double squares = 0;
  size_t a = 0;
  for (size_t b : ends) {
    const double level = cp_median_of(y, a, b);
    for (size_t i = a; i < b; ++i) {
      const double r = std::clamp(y[i] - level, -cap, cap);
      squares += r * r;
    }
    a = b;
  }
  if (y.size() <= ends.size()) return 0;  // no degree of freedom left (segments of one run)
  return std::sqrt(squares / static_cast<double>(y.size() - ends.size()));
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
  const size_t n = values.size();
  const size_t m = std::max<size_t>(min_segment, 1);
  if (n < 2 * m) return {};
  const CpPrefixSums sums(values);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // best[t]: the least cost of values [0, t); last[t]: its last split point.
  std::vector<double> best(n + 1, kInf);
  std::vector<size_t> last(n + 1, 0);
  best[0] = -penalty;
  // Candidates for the last split point, with the step from which each may be
  // pruned. Killick et al.'s pruning: once best[tau] + cost(tau, t) >= best[t],
  // tau is never the last split point of [0, T) for T >= t + m (there t itself
  // is a candidate, and cost(tau, t) + cost(t, T) <= cost(tau, T)); for T
  // closer than m to t, t is not yet a candidate, so tau stays until then.
  struct Candidate {
    size_t tau;
    size_t prune_from;
  };
  constexpr size_t kNever = std::numeric_limits<size_t>::max();
  std::vector<Candidate> candidates{{0, kNever}};
  for (size_t t = m; t <= n; ++t) {
    // tau = t - m becomes a candidate once [tau, t) is long enough, if
    // [0, tau) can itself be segmented (tau >= m).
    if (t >= 2 * m) candidates.push_back({t - m, kNever});
    std::erase_if(candidates, [t](const Candidate& c) { return c.prune_from <= t; });
    for (const Candidate& c : candidates) {
      const double f = best[c.tau] + sums.cost(c.tau, t) + penalty;
      if (f < best[t]) {
        best[t] = f;
        last[t] = c.tau;
      }
    }
    for (Candidate& c : candidates)
      if (c.prune_from == kNever && best[c.tau] + sums.cost(c.tau, t) >= best[t])
        c.prune_from = t + m;
  }
  std::vector<size_t> splits;
  for (size_t t = last[n]; t > 0; t = last[t]) splits.push_back(t);
  std::reverse(splits.begin(), splits.end());
  return splits;
}

std::vector<ChangePoint> find_change_points(std::span<const double> values,
                                            const ChangePointOptions& options) {
  cp_check_options(options);
  const bool relative = options.scale == Scale::kRelative;
  // The runs with a value: their input indices, values, and working values.
  std::vector<size_t> index;
  std::vector<double> raw, y;
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
  }
  const size_t n = y.size();
  const size_t m = options.min_segment;
  if (n < 2 * m) return {};

  double floor = options.noise_floor;
  if (!relative) {
    std::vector<double> magnitude(raw.size());
    std::transform(raw.begin(), raw.end(), magnitude.begin(), [](double v) { return std::abs(v); });
    const double typical = cp_median(magnitude);
    const double level =
        typical > 0 ? typical : *std::max_element(magnitude.begin(), magnitude.end());
    if (level == 0) return {};  // all zero: nothing moved
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
  std::vector<size_t> bounds = pelt_mean_shift(centred, options.beta * sigma * sigma * log_n, m);
  // The MAD of a few differences is a rough estimate (about +-25 % for 20
  // runs), and an underestimate lowers the penalty by its square. The residual
  // noise around the segments just found uses every run; when it is the
  // larger, segment again with it. This only raises sigma, so it only removes
  // steps (false steps in noise-only series of 20 runs at 10 % noise, beta 7:
  // 1.4 % without, 0.3 % with).
  if (!bounds.empty()) {
    const double residual = cp_residual_sigma(centred, bounds, limit);
    if (residual > sigma) {
      sigma = residual;
      bounds = pelt_mean_shift(centred, options.beta * sigma * sigma * log_n, m);
    }
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
  return out;
}

}  // namespace sb::history
