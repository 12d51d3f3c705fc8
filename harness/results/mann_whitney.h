#pragma once
// The Mann–Whitney U test (Wilcoxon rank-sum), two-sided, as
// scipy.stats.mannwhitneyu(x, y, alternative="two-sided") computes it:
//   - U1 = R1 - n1(n1+1)/2 from mid-ranks, U = max(U1, n1·n2 - U1);
//   - exact: p = 2·P(U' >= U) under H0, from the exact null distribution
//     (no tie correction);
//   - asymptotic: normal approximation with the tie-corrected variance and a
//     continuity correction of 0.5; p = 2·(1 - Φ(z)), clipped to 1.
// Auto (scipy's default): exact when some sample has at most 8 values and
// there are no ties, asymptotic otherwise.
#include <span>

namespace sb::results {

enum class MwuMethod { kAuto, kExact, kAsymptotic };

struct MannWhitneyResult {
  double u1 = 0;       // U statistic of x (scipy's `statistic`)
  double p = 1;        // two-sided p-value
  bool exact = false;  // the method used
};

// Throws std::invalid_argument for an empty sample or a NaN.
MannWhitneyResult mann_whitney_u(std::span<const double> x, std::span<const double> y,
                                 MwuMethod method = MwuMethod::kAuto);

}  // namespace sb::results
