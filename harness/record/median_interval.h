#pragma once
// The distribution-free confidence interval of a median from order
// statistics (the sign test's interval; Conover, "Practical Nonparametric
// Statistics", 3.2): of n samples sorted x_(1) <= ... <= x_(n), the interval
// [x_(j), x_(n+1-j)] holds the population median with probability
// 1 - 2 P(B <= j - 1), B ~ Binomial(n, 1/2), whatever the distribution
// (continuous). j is the largest rank that keeps each tail at most 2.5 %,
// so the coverage is at least 95 %. With n < 6 not even the sample range
// reaches 95 % (2 * 2^-n > 5 %): the interval is then the range, j = 1, and
// its coverage, 1 - 2^(1-n), says how much less it holds (93.75 % at 5, 0 at
// 1). A record keeps the interval per series (record/timing_record.h).
#include <cstddef>

namespace sb::record {

struct MedianRanks {
  size_t lower = 0;     // j, 1-based; 0 only for n = 0
  size_t upper = 0;     // n + 1 - j
  double coverage = 0;  // 1 - 2 P(B <= j - 1): at least 0.95 when n >= 6
};

// The ranks of the 95 % interval of the median of n samples.
MedianRanks median_ci_ranks(size_t n);

}  // namespace sb::record
