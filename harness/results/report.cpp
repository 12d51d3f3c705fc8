#include "results/report.h"

#include <filesystem>
#include <string_view>

#include "core/atomic_file.h"
#include "core/bounded_text.h"
#include "results/banner.h"
#include "results/noisy_jobs.h"
#include "results/ranking_tables.h"
#include "results/record_groups.h"
#include "results/report_columns.h"
#include "results/sessions.h"
#include "results/stability_table.h"

namespace sb::results {

using core::write_file_atomically;
using record::JobRecord;

namespace {

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

// ('_' inside words is not emphasis in CommonMark.)
std::string markdown_text(const std::string& s) {
  std::string out;
  std::string line = s;
  for (char& c : line)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  for (char c : core::bounded_text(line, core::kMessageChars)) {
    if (std::string_view("\\`*[]<>|&").find(c) != std::string_view::npos)
      (out += '\\') += c;
    else
      out += c;
  }
  return out;
}

std::string make_csv(const std::vector<JobRecord>& records) {
  std::string out;
  for (const auto& c : report_columns()) out += (out.empty() ? "" : ",") + csv_escape(c.header);
  out += "\n";
  for (const auto& r : records) {
    std::string row;
    for (const auto& c : report_columns())
      row += (&c == &report_columns().front() ? "" : ",") + csv_escape(c.cell(r));
    out += row + "\n";
  }
  return out;
}

std::string make_markdown(const std::vector<JobRecord>& records, const std::string& title) {
  std::string out = "# " + markdown_text(title) + "\n\n";
  if (!records.empty()) {
    const JobRecord& r0 = records.front();
    // Plain escaped text, not code spans: a backtick in a record's field
    // would end the span, and escapes do not work inside one.
    out += "Backend " + markdown_text(r0.backend) + ", renderer " + markdown_text(r0.gl_renderer) +
           ", timing source " + markdown_text(r0.timing_source) +
           ". Error is measured on the visibility buffer against the " + "ray-traced reference" +
           (r0.reference ? ": " + markdown_text(reference_label(*r0.reference)) : std::string()) +
           ".\n";
    out += markdown_banners(report_banners(records));  // mixed hosts or sessions
    if (r0.second_reference)
      out += "The second_ columns are the same errors against a second reference: " +
             markdown_text(reference_label(r0.second_reference->reference)) +
             "; mc_noise_share is the share of the penumbra MSE against the Monte Carlo " +
             "reference that its noise explains.\n";
  }
  const Sessions sessions(records);  // a column of their letters when mixed
  const std::vector<const ReportColumn*> columns = sessions.marked(group_table_columns(records));
  for (const RecordGroup& g : by_scene_and_resolution(records)) {
    out += "\n## " + markdown_text(g.key) + "\n\n|";
    std::string rule = "|";
    for (const ReportColumn* c : columns) {
      out += std::string(" ") + markdown_text(c->header) + " |";
      rule += c->numeric() ? "---:|" : "---|";
    }
    out += "\n" + rule + "\n";
    for (const JobRecord* r : g.records) {
      out += "|";
      for (const ReportColumn* c : columns) out += " " + markdown_text(c->cell(*r)) + " |";
      out += "\n";
    }
    if (const std::string legend = noisy_legend(g.records); !legend.empty())
      out += std::string("\n") + kNoisyMark + " " + markdown_text(legend) + "\n";
    out += ranking_markdown(g.records);
  }
  return out + stability_markdown(records);
}

void write_reports(const std::string& run_dir, const std::vector<JobRecord>& records,
                   const std::string& title) {
  namespace fs = std::filesystem;
  write_file_atomically((fs::path(run_dir) / "results.csv").string(), make_csv(records));
  write_file_atomically((fs::path(run_dir) / "summary.md").string(), make_markdown(records, title));
}

}  // namespace sb::results
