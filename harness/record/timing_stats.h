#pragma once
// Summary statistics of per-frame times: robust (median, p10, p90) plus the
// coefficient of variation, so noisy machines show how noisy they were.
// A record keeps them with the samples (record/timing_record.h, Series).
#include <cstddef>
#include <vector>

namespace sb::record {

struct TimingStats {
  size_t count = 0;
  double median = 0, p10 = 0, p90 = 0, mean = 0, min = 0, max = 0;
  double cv = 0;  // standard deviation / mean (population)
};

// Percentiles by linear interpolation between order statistics (as numpy's
// default), so p50 of {1,2,3,4} is 2.5.
TimingStats summarize(std::vector<double> samples_ms);

}  // namespace sb::record
