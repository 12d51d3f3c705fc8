#include "results/stability_table.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/format_number.h"
#include "results/report.h"

namespace sb::results {

using core::format_number;
using record::FlickerRecord;
using record::JobRecord;
using record::JobStatus;
using record::kFlickerFloor;
using record::StabilityRecord;

const char* to_string(StabilityVerdict v) {
  switch (v) {
    case StabilityVerdict::Ok:
      return "ok";
    case StabilityVerdict::Degraded:
      return "degraded";
    case StabilityVerdict::Broken:
      return "broken";
    case StabilityVerdict::Failed:
      return "failed";
    case StabilityVerdict::Skipped:
      break;
  }
  return "skipped";
}

StabilityCell stability_cell(const JobRecord& r) {
  StabilityCell c;
  if (r.status == JobStatus::Skipped) {
    c.verdict = StabilityVerdict::Skipped;
    c.figure = r.reason.value_or("");
    return c;
  }
  if (r.visibility_check) {
    const auto& v = *r.visibility_check;
    if (v.nonfinite + v.below_0 + v.above_1 > 0) {
      c.verdict = StabilityVerdict::Broken;
      c.figure = std::to_string(v.nonfinite) + " NaN/Inf, " + std::to_string(v.below_0) +
                 " below 0, " + std::to_string(v.above_1) + " above 1";
      return c;
    }
  }
  if (r.status == JobStatus::Failed) {
    c.verdict = StabilityVerdict::Failed;
    c.figure = r.reason.value_or("");
    return c;
  }
  std::vector<std::string> figures, problems;
  const double rmse = r.metrics ? r.metrics->visibility.all.rmse : 0.0;
  const StabilityRecord* s = r.stability ? &*r.stability : nullptr;
  if (r.metrics) {
    if (s && rmse > s->max_rmse)
      problems.push_back("rmse " + format_number("%.4f", rmse) + " > " +
                         format_number("%g", s->max_rmse));
    else
      figures.push_back("rmse " + format_number("%.4f", rmse));
  }
  if (s && s->flicker) {
    const FlickerRecord& f = *s->flicker;
    const std::string text = "flicker " + format_number("%.2e", f.mean) + ", popping " +
                             format_number("%.2e", f.frac_over_005) + " (reference " +
                             format_number("%.2e", f.reference_mean) + ", " +
                             format_number("%.2e", f.reference_frac_over_005) + ")";
    if (f.mean > s->flicker_factor * f.reference_mean + kFlickerFloor ||
        f.frac_over_005 > s->flicker_factor * f.reference_frac_over_005 + kFlickerFloor)
      problems.push_back(text);
    else
      figures.push_back(text);
  }
  if (s) {
    std::string stiff;
    for (const auto& [name, p] : s->sensitivity)
      if (p.stiff)
        stiff += (stiff.empty() ? "" : ", ") + name + " " + format_number("%.3g", p.relative);
    if (!stiff.empty()) problems.push_back("stiff: " + stiff);
  }
  c.verdict = problems.empty() ? StabilityVerdict::Ok : StabilityVerdict::Degraded;
  std::string text;
  for (const auto* list : {&problems, &figures})
    for (const std::string& t : *list) text += (text.empty() ? "" : "; ") + t;
  c.figure = text;
  return c;
}

std::optional<StabilityTable> stability_table(const std::vector<JobRecord>& records) {
  if (std::none_of(records.begin(), records.end(),
                   [](const JobRecord& r) { return r.stability.has_value(); }))
    return std::nullopt;
  std::vector<std::string> resolutions;
  for (const auto& r : records)
    if (std::find(resolutions.begin(), resolutions.end(), r.resolution) == resolutions.end())
      resolutions.push_back(r.resolution);
  const auto case_of = [&](const JobRecord& r) {
    return resolutions.size() > 1 ? r.scene_variant + " @ " + r.resolution : r.scene_variant;
  };
  StabilityTable t;
  std::map<std::string, size_t> case_index, technique_index;
  for (const auto& r : records) {
    const std::string c = case_of(r);
    if (case_index.emplace(c, t.cases.size()).second) t.cases.push_back(c);
    if (technique_index.emplace(r.technique_variant, t.techniques.size()).second)
      t.techniques.push_back(r.technique_variant);
  }
  t.cells.assign(t.techniques.size(), std::vector<const JobRecord*>(t.cases.size(), nullptr));
  for (const auto& r : records)
    t.cells[technique_index[r.technique_variant]][case_index[case_of(r)]] = &r;
  return t;
}

std::string stability_markdown(const std::vector<JobRecord>& records) {
  const auto t = stability_table(records);
  if (!t) return "";
  std::string out =
      "\n## Stability\n\nTechnique × case (docs/stability.md): ok, degraded (RMSE over the "
      "case's threshold, flicker over the reference's by the set factor, or a stiff "
      "parameter) or broken (V not finite or outside [0, 1]), with the figures behind it.\n\n"
      "| technique |";
  std::string rule = "|---|";
  for (const auto& c : t->cases) {
    out += " " + markdown_text(c) + " |";
    rule += "---|";
  }
  out += "\n" + rule + "\n";
  for (size_t i = 0; i < t->techniques.size(); ++i) {
    out += "| " + markdown_text(t->techniques[i]) + " |";
    for (const JobRecord* r : t->cells[i]) {
      if (r == nullptr) {
        out += " |";
        continue;
      }
      const StabilityCell c = stability_cell(*r);
      out += std::string(" **") + to_string(c.verdict) + "**" +
             (c.figure.empty() ? "" : ": " + markdown_text(c.figure)) + " |";
    }
    out += "\n";
  }
  return out;
}

}  // namespace sb::results
