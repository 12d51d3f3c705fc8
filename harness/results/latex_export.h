#pragma once
// `report --latex`: the paper tables (results/latex_tables.h), the rankings
// by time with their ties (results/ranking_tables.h) and the
// error-against-time CSVs for pgfplots (results/pgf_csv.h) of a run, one of
// each per (scene variant, resolution), in one folder with tables.tex, a
// document that \input's every table and draws every CSV with pgfplots, so
// that `pdflatex tables.tex` shows them all (docs/paper.md).
#include <string>
#include <vector>

#include "record/figures.h"
#include "record/job_record.h"

namespace sb::results {

struct LatexOptions {
  std::vector<std::string> columns;  // report column names; empty: the default ones
  std::string error_metric = record::kDefaultErrorMetric;  // the CSVs' error (--metric)
  int digits = 3;                                          // significant digits in the tables
  std::string title = "shadowbench";                       // tables.tex's heading
};

struct LatexFiles {
  std::vector<std::string> tables;  // table-<scene>-<WxH>.tex, in group order
  std::vector<std::string> csvs;    // error-time-<scene>-<WxH>.csv, likewise
  // ranking-<scene>-<WxH>.tex (results/ranking_tables.h), for the groups
  // with two or more variants ranked by time
  std::vector<std::string> rankings;
  std::string document;  // tables.tex
};

// Writes the files into out_dir (created if missing; each atomically).
// Throws InputError for an unknown column or metric before writing anything.
LatexFiles write_latex(const std::vector<record::JobRecord>& records, const std::string& out_dir,
                       const LatexOptions& options = {});

}  // namespace sb::results
