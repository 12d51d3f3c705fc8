// `shadowbench report`: tables, charts and index.html of a run folder.
// report and compare read run folders that anyone may have written: a record
// that does not follow the schema is bad input (read_job_records names the
// file, the line and the JSON pointer), not an internal error.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/shared.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "results/charts.h"
#include "results/compare.h"
#include "results/html_report.h"
#include "results/latex_export.h"
#include "results/latex_tables.h"
#include "results/report.h"
#include "store/results_store.h"

namespace sb::cli {

using core::InputError;
using core::kExitOk;
using results::ChartFile;
using results::ChartOptions;
using results::latex_columns;
using results::LatexFiles;
using results::LatexOptions;
using results::make_markdown;
using results::ReportChart;
using results::write_charts;
using results::write_html_report;
using results::write_latex;
using results::write_reports;
using store::read_job_records;

namespace {

struct ReportArgs {
  std::string run_dir;
  std::string out;
  std::string metric = results::CompareOptions{}.metric;
  bool no_viewer_data = false;  // the image viewer without its data files
  bool latex = false;           // paper tables
  std::vector<std::string> latex_columns;
  std::string chart_style = "default";  // default or paper
  CiOutputs ci;
};

int cmd_report(const ReportArgs& a) {
  if (a.run_dir.empty())
    throw InputError("", "command line", "expected one RUN_DIR (see shadowbench report --help)");
  const std::string& run_dir = a.run_dir;
  const auto records = read_job_records(run_dir);
  const std::string title =
      records.empty() ? "shadowbench" : records[0].experiment + " (" + records[0].run_id + ")";
  if (a.latex) latex_columns(a.latex_columns, records);  // an unknown column before any output
  // Charts and index.html go to --out, by default RUN_DIR/report.
  const std::string out =
      a.out.empty() ? (std::filesystem::path(run_dir) / "report").string() : a.out;
  // A viewer folder that is not the report's, before any output.
  results::check_viewer_folder(out);
  // Its default folder is the run folder's: not followed if a symlink.
  if (a.out.empty())
    core::make_own_folder(run_dir, "report");
  else
    std::filesystem::create_directories(out);
  write_reports(run_dir, records, title);
  std::printf("%s", make_markdown(records, title).c_str());
  ChartOptions chart_options;
  chart_options.error_metric = a.metric;
  chart_options.style = a.chart_style;
  std::vector<ReportChart> charts;
  for (const ChartFile& c : write_charts(records, out, chart_options)) {
    charts.push_back({c.title, c.svg, c.png});
    std::printf("chart: %s (.png%s)\n", c.svg.c_str(), c.pdf.empty() ? "" : ", .pdf");
  }
  if (a.latex) {
    LatexOptions latex;
    latex.columns = a.latex_columns;
    latex.error_metric = a.metric;
    latex.title = title;
    const LatexFiles files =
        write_latex(records, (std::filesystem::path(out) / "latex").string(), latex);
    for (size_t i = 0; i < files.tables.size(); ++i)
      std::printf("latex: %s, %s\n", files.tables[i].c_str(), files.csvs[i].c_str());
    for (const std::string& ranking : files.rankings) std::printf("latex: %s\n", ranking.c_str());
    std::printf("latex: %s (pdflatex tables.tex)\n", files.document.c_str());
  }
  write_html_report(records, run_dir, out, charts, title, !a.no_viewer_data);
  std::printf("report: %s\n", (std::filesystem::path(out) / "index.html").string().c_str());
  write_ci_outputs(a.ci, records);
  return kExitOk;
}

}  // namespace

void add_report_command(CommandLine& cl) {
  const auto a = std::make_shared<ReportArgs>();
  CLI::App* report = cl.add_command(
      cl.app(), "report",
      "Write the tables (CSV, Markdown), the charts (SVG, PNG) and an offline index.html of "
      "a run folder.",
      "shadowbench report results/quick --metric visibility.penumbra.rmse",
      [a] { return cmd_report(*a); });
  add_argument(report, "RUN_DIR", a->run_dir, "a folder `run` wrote");
  report->add_option("--out", a->out, "where charts and index.html go (default: RUN_DIR/report)")
      ->type_name("DIR");
  add_metric(report, a->metric, "the error on the charts' y axis");
  report->add_flag("--no-viewer-data", a->no_viewer_data,
                   "no data files for the image viewer (about 5.3 bytes per pixel per image): it "
                   "then shows the PNGs, without V, error or pixel values");
  CLI::Option* latex = report->add_flag(
      "--latex", a->latex,
      "also write booktabs tables and pgfplots CSVs of error against time into OUT/latex, "
      "with tables.tex showing them all (docs/paper.md)");
  report
      ->add_option("--latex-columns", a->latex_columns,
                   "the tables' columns after the technique, comma-separated report columns "
                   "(default: frame_ms,x_control,rmse,penumbra_rmse,ssim,flip, those with values)")
      ->type_name("COLS")
      ->delimiter(',')
      ->default_str("")  // not "[]"
      ->needs(latex);
  add_choice(report, "--style", a->chart_style, {"default", "paper"},
             "the charts' style: paper draws them 3.3 in wide in Computer Modern, as PDF too");
  add_ci_outputs(report, a->ci);
}

}  // namespace sb::cli
