#include "record/median_interval.h"

#include <cmath>

namespace sb::record {

MedianRanks median_ci_ranks(size_t n) {
  if (n == 0) return {};
  // P(B <= k) summed upwards in log space (n goes to 100000 frames), until a
  // tail would pass 2.5 %: j - 1 is the last k whose cdf stays within it.
  const double log_half_n = double(n) * std::log(0.5);
  const double log_n_fact = std::lgamma(double(n) + 1.0);
  double cdf = 0.0;        // P(B <= k - 1) before step k
  double kept_tail = 0.0;  // P(B <= j - 1) of the j found so far
  size_t j = 0;
  for (size_t k = 0; k <= n / 2; ++k) {
    cdf += std::exp(log_n_fact - std::lgamma(double(k) + 1.0) - std::lgamma(double(n - k) + 1.0) +
                    log_half_n);
    if (cdf > 0.025) break;
    j = k + 1;
    kept_tail = cdf;
  }
  if (j == 0) {  // n < 6: the range, which holds the median less often
    j = 1;
    kept_tail = std::exp(log_half_n);
  }
  return {j, n + 1 - j, 1.0 - 2.0 * kept_tail};
}

}  // namespace sb::record
