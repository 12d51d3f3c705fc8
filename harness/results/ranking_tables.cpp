#include "results/ranking_tables.h"

#include <string_view>

#include "core/format_number.h"
#include "results/html_page.h"
#include "results/latex_tables.h"
#include "results/rank_ties.h"
#include "results/report.h"

namespace sb::results {

using core::format_number;
using record::JobRecord;

namespace {

// The cells of one row: rank, technique, median, samples, p against above.
std::vector<std::string> row_cells(const RankEntry& e) {
  return {rank_cell(e), e.record->technique_variant, format_number("%.4g", e.median),
          std::to_string(e.count),
          e.p_adjusted ? format_number("%.3g", *e.p_adjusted) : std::string()};
}

std::vector<std::string> headers(const Ranking& r) {
  return {"rank", "technique", "median " + ranked_quantity(r), "samples", "p vs above (Holm)"};
}

}  // namespace

std::string ranking_markdown(const std::vector<const JobRecord*>& group) {
  const Ranking r = rank_by_time(group);
  if (r.entries.size() < 2) return "";
  std::string out = "\nRanking by time:\n\n|";
  for (const std::string& h : headers(r)) out += " " + markdown_text(h) + " |";
  out += "\n|---:|---|---:|---:|---:|\n";
  for (const RankEntry& e : r.entries) {
    out += "|";
    for (const std::string& c : row_cells(e)) out += " " + markdown_text(c) + " |";
    out += "\n";
  }
  return out + "\n" + markdown_text(ranking_legend(r)) + "\n";
}

std::string ranking_html(const std::vector<const JobRecord*>& group) {
  const Ranking r = rank_by_time(group);
  if (r.entries.size() < 2) return "";
  std::string out = "<div class=\"table-wrap\"><table class=\"sortable ranking\">\n<thead><tr>";
  const std::vector<std::string> h = headers(r);
  for (std::size_t i = 0; i < h.size(); ++i)
    out +=
        std::string("<th") + (i == 1 ? "" : " class=\"num\"") + ">" + html_escape(h[i]) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const RankEntry& e : r.entries) {
    out += e.tied_with_above ? "<tr class=\"tie\">" : "<tr>";
    const std::vector<std::string> cells = row_cells(e);
    for (std::size_t i = 0; i < cells.size(); ++i)
      out += std::string("<td class=\"") + (i == 1 ? "name" : "num") + "\">" +
             html_escape(cells[i]) + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table></div>\n<p class=\"note ranking-legend\">" +
         html_escape(ranking_legend(r)) + "</p>\n";
}

std::string ranking_latex(const std::vector<const JobRecord*>& group, int digits) {
  const Ranking r = rank_by_time(group);
  if (r.entries.size() < 2) return "";
  std::string out = "% needs \\usepackage{booktabs}\n\\begin{tabular}{rlrrr}\n\\toprule\n";
  std::string header;
  for (const std::string& h : headers(r)) header += (header.empty() ? "" : " & ") + latex_text(h);
  out += header + " \\\\\n\\midrule\n";
  for (const RankEntry& e : r.entries) {
    out += std::to_string(e.rank) + (e.tied_with_above ? " $\\approx$" : "") + " & " +
           latex_text(e.record->technique_variant) + " & " + latex_number(e.median, digits) +
           " & " + std::to_string(e.count) + " & " +
           (e.p_adjusted ? latex_number(*e.p_adjusted, digits) : std::string()) + " \\\\\n";
  }
  return out + "\\bottomrule\n\\end{tabular}\n";
}

std::string ranking_latex_legend(const std::vector<const JobRecord*>& group) {
  // The one legend, escaped; its two signs outside pdflatex's default
  // encoding (latex_text writes them as code points) set as LaTeX.
  std::string out = latex_text(ranking_legend(rank_by_time(group)));
  for (const auto& [code, latex] : {std::pair<std::string_view, std::string_view>{
                                        "\\textless{}U+2248\\textgreater{}", "$\\approx$"},
                                    {"\\textless{}U+2013\\textgreater{}", "--"}})
    for (size_t at = out.find(code); at != std::string::npos; at = out.find(code, at))
      out.replace(at, code.size(), latex);
  return out;
}

}  // namespace sb::results
