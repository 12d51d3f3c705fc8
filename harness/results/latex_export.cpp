#include "results/latex_export.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "core/atomic_file.h"
#include "results/banner.h"
#include "results/latex_tables.h"
#include "results/pgf_csv.h"
#include "results/ranking_tables.h"
#include "results/record_groups.h"
#include "results/sessions.h"

namespace sb::results {

using core::write_file_atomically;
using record::JobRecord;

namespace {

namespace fs = std::filesystem;

// A name that \input and pgfplots take as it is: letters, digits and '-'.
std::string latex_file_stem(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (keep)
      out += c;
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "group" : out;
}

struct LatexGroup {
  std::string name;  // "scene @ WxH"
  std::string stem;  // unique among the groups
  std::vector<const JobRecord*> records;
};

std::vector<LatexGroup> latex_groups(const std::vector<JobRecord>& records) {
  std::vector<LatexGroup> groups;
  std::set<std::string> stems;
  for (RecordGroup& group : by_scene_and_resolution(records)) {
    LatexGroup g;
    const JobRecord& r = *group.records.front();
    g.name = std::move(group.key);
    const std::string base = latex_file_stem(r.scene_variant + "-" + r.resolution);
    g.stem = base;
    for (int n = 2; !stems.insert(g.stem).second; ++n) g.stem = base + "-" + std::to_string(n);
    g.records = std::move(group.records);
    groups.push_back(std::move(g));
  }
  return groups;
}

// tables.tex's pgfplots figure of one group's CSV: each point with its
// p10–p90 frame time as error bars and its own legend entry (names beside
// close points would overlap), the control hollow and grey, and the Pareto
// front as a step line.
std::string latex_figure(const std::string& csv, const std::vector<ErrorTimeRow>& rows,
                         const std::string& metric, const std::string& group) {
  std::size_t longest = 0;
  for (const ErrorTimeRow& r : rows)
    longest = std::max(longest, r.record->technique_variant.size());
  std::string out = "\n\\begin{figure}[htbp]\n\\centering\n\\begin{tikzpicture}\n";
  // Times span orders of magnitude (a shadow map to an accumulation
  // reference), so the time axis is logarithmic, as on the report's chart.
  out += "\\begin{axis}[width=0.8\\textwidth, height=0.5\\textwidth, xlabel={Frame time (ms)},\n";
  out += "  xmode=log, log ticks with fixed point,\n";
  out += "  ylabel={" + latex_text(metric) + "},\n";
  out += "  scaled y ticks=false, yticklabel style={/pgf/number format/fixed},\n";
  out += "  legend style={at={(0.5,-0.2)}, anchor=north, draw=none, font=\\scriptsize},\n";
  out +=
      "  legend cell align=left, legend columns=" + std::string(longest <= 36 ? "2" : "1") + ",\n";
  out += "  error bars/error bar style={thin}]\n";
  // One plot per row: the other rows skipped by index.
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out += "\\addplot+[only marks,";
    if (rows[i].control) out += " mark=o, gray,";
    out += " error bars/.cd, x dir=both, x explicit]\n";
    out += "  table[x=time_ms, y=error, col sep=comma,\n";
    out += "    x error plus expr=\\thisrow{time_p90_ms}-\\thisrow{time_ms},\n";
    out += "    x error minus expr=\\thisrow{time_ms}-\\thisrow{time_p10_ms},\n";
    if (i > 0) out += "    skip coords between index={0}{" + std::to_string(i) + "},\n";
    out += "    skip coords between index={" + std::to_string(i + 1) + "}{" +
           std::to_string(rows.size()) + "}]\n";
    out += "  {" + csv + "};\n";
    out += "\\addlegendentry{" + latex_text(rows[i].record->technique_variant) +
           (rows[i].control ? " (control)" : "") + "}\n";
  }
  // The front's rows only: the others' y becomes NaN, which pgfplots drops
  // (restrict expr to domain made them unbounded, and the step line ran
  // down to the axis at the first of them).
  out += "\\addplot[const plot, black, unbounded coords=discard,\n";
  out += "  y filter/.expression={\\thisrow{pareto} == 1 ? y : nan}]\n";
  out += "  table[x=time_ms, y=error, col sep=comma] {" + csv + "};\n";
  out += "\\addlegendentry{Pareto front}\n";
  out += "\\end{axis}\n\\end{tikzpicture}\n";
  out += "\\caption{" + latex_text(metric + " against frame time: " + group);
  out +=
      " (bars: p10--p90 of the frame time; the line: the Pareto front, without the "
      "control)}\n\\end{figure}\n";
  return out;
}

}  // namespace

LatexFiles write_latex(const std::vector<JobRecord>& records, const std::string& out_dir,
                       const LatexOptions& options) {
  const Sessions sessions(records);  // a column of their letters when mixed
  const std::vector<const ReportColumn*> columns =
      sessions.marked(latex_columns(options.columns, records));
  struct Texts {
    std::string table, csv;
    std::vector<ErrorTimeRow> rows;
    std::string ranking;
    bool plotted = false;
  };
  const std::vector<LatexGroup> groups = latex_groups(records);
  std::vector<Texts> texts;
  for (const LatexGroup& g : groups) {  // everything made, and checked, before a file is written
    Texts t{make_latex_table(g.records, columns, options.digits),
            make_error_time_csv(g.records, options.error_metric),
            error_time_rows(g.records, options.error_metric),
            ranking_latex(g.records, options.digits)};
    t.plotted = !t.rows.empty();
    texts.push_back(std::move(t));
  }

  // latex/ is the tool's own folder in the report's: a symlink planted there
  // is refused, never written through.
  const fs::path out_path(out_dir);
  core::make_own_folder(out_path.parent_path().string(), out_path.filename().string(),
                        "report --latex: ");
  LatexFiles files;
  std::string doc =
      "% shadowbench report --latex: every table and error-against-time plot of the run.\n"
      "% Build with: pdflatex tables.tex\n"
      "\\documentclass{article}\n"
      "\\usepackage[margin=2cm]{geometry}\n"
      "\\usepackage{booktabs}\n"
      "\\usepackage{graphicx}\n"
      "\\usepackage{pgfplots}\n"
      "\\pgfplotsset{compat=1.18}\n"
      "% A table wider than the text is scaled down to its width, never up.\n"
      "\\newsavebox{\\sbtable}\n"
      "\\newcommand{\\sbfit}[1]{\\sbox{\\sbtable}{#1}%\n"
      "  \\ifdim\\wd\\sbtable>\\linewidth\\resizebox{\\linewidth}{!}{\\usebox{\\sbtable}}%\n"
      "  \\else\\usebox{\\sbtable}\\fi}\n"
      "\\begin{document}\n"
      "\\section*{" +
      latex_text(options.title) + "}\n" + latex_banners(report_banners(records));
  for (size_t i = 0; i < groups.size(); ++i) {
    const LatexGroup& g = groups[i];
    const std::string table = "table-" + g.stem + ".tex", csv = "error-time-" + g.stem + ".csv";
    files.tables.push_back((fs::path(out_dir) / table).string());
    files.csvs.push_back((fs::path(out_dir) / csv).string());
    write_file_atomically(files.tables.back(), texts[i].table);
    write_file_atomically(files.csvs.back(), texts[i].csv);
    doc += "\n\\begin{table}[htbp]\n\\centering\n\\caption{" + latex_text(g.name) +
           "}\n\\small\n\\sbfit{\\input{" + table + "}}\n\\end{table}\n";
    if (!texts[i].ranking.empty()) {
      const std::string ranking = "ranking-" + g.stem + ".tex";
      files.rankings.push_back((fs::path(out_dir) / ranking).string());
      write_file_atomically(files.rankings.back(), texts[i].ranking);
      doc +=
          "\n\\begin{table}[htbp]\n\\centering\n\\caption{Ranking by time: " + latex_text(g.name) +
          ". " + ranking_latex_legend(g.records) + "}\n\\small\n\\sbfit{\\input{" + ranking +
          "}}\n\\end{table}\n";
    }
    // A page now and then: LaTeX holds at most 18 floats in waiting.
    const std::string page_break = (i + 1) % 4 == 0 ? "\\clearpage\n" : "";
    if (!texts[i].plotted) {
      doc += page_break;
      continue;
    }
    doc += latex_figure(csv, texts[i].rows, options.error_metric, g.name);
    doc += page_break;
  }
  doc += "\n\\end{document}\n";
  files.document = (fs::path(out_dir) / "tables.tex").string();
  write_file_atomically(files.document, doc);
  return files;
}

}  // namespace sb::results
