#pragma once
// Rankings by time with their uncertainty: per (scene variant,
// resolution), the ok jobs but the timing control (results/control_baseline.h)
// in order of the median of their per-frame samples, and for each pair of
// neighbours in that order whether their difference is significant.
//
//  - Samples: the per-frame ratios to the control (timing.control.frame_ratio,
//    each frame over the control frame timed next to it: the ratio cancels
//    what the machine adds to both) when every ranked job has them against
//    one control; else the frame times (timing.frame.samples_ms).
//  - Test: two-sided Mann–Whitney U (results/mann_whitney.h, as `compare`
//    uses it) on each adjacent pair, the p-values Holm-adjusted over the
//    group's adjacent pairs (results/multiple_testing.h), so that the chance
//    of calling any one step of the ranking real when none is stays <= alpha.
//  - A pair whose adjusted p is >= alpha is a tie ("≈"). Ties chain: a tie
//    group is a run of neighbours joined by ties, and its two ends may still
//    differ significantly (only neighbours are tested).
// A job without samples, or with a NaN among them, is left out of the ranking.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

inline constexpr double kRankAlpha = 0.05;  // the tables' alpha (docs/results.md)

enum class RankSamples { kControlRatio, kFrameMs };

struct RankEntry {
  const record::JobRecord* record = nullptr;
  int rank = 0;           // 1-based place by median
  double median = 0;      // of the samples ranked
  std::size_t count = 0;  // samples
  // Against the entry ranked just above (none for the first): the
  // Holm-adjusted p, and whether it is >= alpha.
  std::optional<double> p_adjusted;
  bool tied_with_above = false;
  int tie_group = 0;  // 1-based; a new group begins at each significant step
};

struct Ranking {
  RankSamples samples = RankSamples::kFrameMs;
  std::string control;  // the control's technique variant, with kControlRatio
  double alpha = kRankAlpha;
  std::vector<RankEntry> entries;  // by rank

  std::size_t pairs_tested() const { return entries.empty() ? 0 : entries.size() - 1; }
};

Ranking rank_by_time(const std::vector<const record::JobRecord*>& group, double alpha = kRankAlpha);

// The rank as a table shows it: "3", or "3 ≈" when tied with the one above.
std::string rank_cell(const RankEntry& e);
// "frame/control ratio" or "frame time (ms)": what the median is of.
std::string ranked_quantity(const Ranking& r);
// One sentence for under a table: what is ranked, on which samples, the
// test, the correction and alpha (plain UTF-8 text, no markup).
std::string ranking_legend(const Ranking& r);

}  // namespace sb::results
