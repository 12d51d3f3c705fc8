#include "results/rank_ties.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "core/format_number.h"
#include "record/timing_stats.h"
#include "results/control_baseline.h"
#include "results/mann_whitney.h"
#include "results/multiple_testing.h"

namespace sb::results {

using core::format_number;
using record::JobRecord;
using record::JobStatus;

namespace {

const std::vector<double>* ratio_samples(const JobRecord& r) {
  if (!r.timing || !r.timing->control || r.timing->control->frame_ratio.samples.empty())
    return nullptr;
  return &r.timing->control->frame_ratio.samples;
}

}  // namespace

Ranking rank_by_time(const std::vector<const JobRecord*>& group, double alpha) {
  Ranking out;
  out.alpha = alpha;
  std::vector<const JobRecord*> ranked;
  for (const JobRecord* r : group)
    if (r->status == JobStatus::Ok && r->timing && !is_control(group, *r)) ranked.push_back(r);

  // Ratios when every ranked job has them against one control.
  const bool ratios =
      !ranked.empty() && std::all_of(ranked.begin(), ranked.end(), [&](const JobRecord* r) {
        return ratio_samples(*r) != nullptr &&
               r->timing->control->technique == ranked[0]->timing->control->technique;
      });
  out.samples = ratios ? RankSamples::kControlRatio : RankSamples::kFrameMs;
  if (ratios) out.control = ranked[0]->timing->control->technique;

  std::vector<const std::vector<double>*> samples;
  for (const JobRecord* r : ranked) {
    const std::vector<double>* s = ratios ? ratio_samples(*r) : &r->timing->frame.samples;
    // No samples, or a NaN among them (which no rank test orders): not ranked.
    if (s->empty() || std::any_of(s->begin(), s->end(), [](double v) { return std::isnan(v); }))
      continue;
    RankEntry e;
    e.record = r;
    e.median = record::summarize(*s).median;
    e.count = s->size();
    out.entries.push_back(e);
    samples.push_back(s);
  }
  // By median; equal medians keep the group's order.
  std::vector<std::size_t> order(out.entries.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out.entries[a].median < out.entries[b].median;
  });
  std::vector<RankEntry> entries;
  std::vector<const std::vector<double>*> sorted_samples;
  for (const std::size_t i : order) {
    entries.push_back(out.entries[i]);
    sorted_samples.push_back(samples[i]);
  }
  out.entries = std::move(entries);

  std::vector<double> p;
  for (std::size_t i = 1; i < out.entries.size(); ++i)
    p.push_back(mann_whitney_u(*sorted_samples[i - 1], *sorted_samples[i]).p);
  const std::vector<double> adjusted = adjust_p_values(p, Correction::kHolm);
  int tie_group = 0;
  for (std::size_t i = 0; i < out.entries.size(); ++i) {
    RankEntry& e = out.entries[i];
    e.rank = int(i + 1);
    if (i > 0) {
      e.p_adjusted = adjusted[i - 1];
      e.tied_with_above = *e.p_adjusted >= alpha;
    }
    if (!e.tied_with_above) ++tie_group;
    e.tie_group = tie_group;
  }
  return out;
}

std::string rank_cell(const RankEntry& e) {
  return std::to_string(e.rank) + (e.tied_with_above ? " \u2248" : "");
}

std::string ranked_quantity(const Ranking& r) {
  return r.samples == RankSamples::kControlRatio ? "frame/control ratio" : "frame time (ms)";
}

std::string ranking_legend(const Ranking& r) {
  const std::string samples =
      r.samples == RankSamples::kControlRatio
          ? "the per-frame ratios to the control " + r.control +
                " (timing.control.frame_ratio: each frame over the control frame timed next "
                "to it)"
          : "the per-frame times (timing.frame.samples_ms; the records have no common control)";
  return "Ranked by the median of " + samples +
         ", the control left out. \u2248: not significantly different from the variant ranked "
         "just above (two-sided Mann\u2013Whitney U, Holm-corrected over the " +
         std::to_string(r.pairs_tested()) + " adjacent pairs, alpha " +
         format_number("%g", r.alpha) + "); ties chain, so the ends of a run of \u2248 may differ.";
}

}  // namespace sb::results
