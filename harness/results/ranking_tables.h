#pragma once
// A (scene variant, resolution)'s ranking by time with its ties
// (results/rank_ties.h) as a small table under the group's summary table:
// Markdown for summary.md, HTML for the report. Columns: rank ("2 ≈" when
// not significantly different from the variant above), technique, the median
// ranked, the samples, and the Holm-adjusted p against the variant above;
// then the legend (ranking_legend). Empty when fewer than two variants rank.
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

std::string ranking_markdown(const std::vector<const record::JobRecord*>& group);
std::string ranking_html(const std::vector<const record::JobRecord*>& group);
// For `report --latex`: a booktabs tabular of the same rows (needs
// \usepackage{booktabs} only; "2 $\approx$"), numbers to `digits`
// significant digits; empty as above.
std::string ranking_latex(const std::vector<const record::JobRecord*>& group, int digits = 3);
// The legend as LaTeX text, for the ranking's caption.
std::string ranking_latex_legend(const std::vector<const record::JobRecord*>& group);

}  // namespace sb::results
