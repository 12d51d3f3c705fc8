#pragma once
// Summary statistics of per-frame times: robust (median, p10, p90) plus the
// coefficient of variation, so noisy machines show how noisy they were, and
// the median's 95 % interval from order statistics (record/median_interval.h).
// A record keeps them with the samples (record/timing_record.h, Series).
#include <cstddef>
#include <vector>

namespace sb::record {

struct TimingStats {
  size_t count = 0;
  double median = 0, p10 = 0, p90 = 0, mean = 0, min = 0, max = 0;
  double cv = 0;  // standard deviation / mean (population)
  // The median's interval: x_(j) and x_(n+1-j), and how often it holds the
  // median (at least 0.95 from 6 samples; the range below that).
  double median_ci_lo = 0, median_ci_hi = 0, median_ci_coverage = 0;
  // Its half-width relative to the median: (hi - lo) / 2 / median (0 when
  // the median is not positive).
  double median_ci_rel() const;
};

// Percentiles by linear interpolation between order statistics (as numpy's
// default), so p50 of {1,2,3,4} is 2.5.
TimingStats summarize(std::vector<double> samples_ms);

}  // namespace sb::record
