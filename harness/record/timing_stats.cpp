#include "record/timing_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "record/median_interval.h"

namespace sb::record {

namespace {
double percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double pos = q * double(sorted.size() - 1);
  const size_t lo = size_t(std::floor(pos));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - double(lo)) * (sorted[hi] - sorted[lo]);
}
}  // namespace

TimingStats summarize(std::vector<double> samples) {
  TimingStats s;
  s.count = samples.size();
  if (samples.empty()) return s;
  std::sort(samples.begin(), samples.end());
  s.median = percentile(samples, 0.5);
  s.p10 = percentile(samples, 0.1);
  s.p90 = percentile(samples, 0.9);
  s.min = samples.front();
  s.max = samples.back();
  s.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / double(samples.size());
  double var = 0.0;
  for (double v : samples) var += (v - s.mean) * (v - s.mean);
  var /= double(samples.size());
  s.cv = s.mean > 0.0 ? std::sqrt(var) / s.mean : 0.0;
  const MedianRanks ranks = median_ci_ranks(samples.size());
  s.median_ci_lo = samples[ranks.lower - 1];
  s.median_ci_hi = samples[ranks.upper - 1];
  s.median_ci_coverage = ranks.coverage;
  return s;
}

double TimingStats::median_ci_rel() const {
  return median > 0.0 ? (median_ci_hi - median_ci_lo) / 2.0 / median : 0.0;
}

}  // namespace sb::record
