#pragma once
// The columns of every table made from records: results.csv, summary.md and
// the HTML report's summary tables all take their columns, headers and cell
// text from this one list (docs/results.md, "Table columns").
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "record/describe.h"
#include "record/job_record.h"

namespace sb::results {

// Which way a figure improves (record/describe.h): the paper tables
// (results/latex_tables.h) set the best value of a column in bold.
using record::Better;

struct ReportColumn {
  const char* name = "";    // how code refers to the column ("frame_ms")
  const char* header = "";  // what the tables show above it
  // For a paper's table: the figure in words ("Frame", "RMSE") and its unit
  // ("ms"; "" for a ratio or a fraction), and which way it improves; the
  // catalogue's (record/figures.h) for a figure of the record.
  const char* label = "";
  const char* unit = "";
  Better better = Better::Neither;
  // Scene and resolution: the Markdown and HTML tables are one per (scene,
  // resolution) and leave these out; the CSV, one table, keeps them.
  bool per_group = false;
  // Figures only some runs have (a second reference's): the Markdown and
  // HTML tables leave the column out when no record has a value for it.
  bool optional = false;
  // Exactly one of the two: a text cell, or a number printed with `format`.
  std::function<std::string(const record::JobRecord&)> text;
  std::function<std::optional<double>(const record::JobRecord&)> number;
  const char* format = nullptr;  // printf format of a number

  bool numeric() const { return number != nullptr; }
  // The cell: the text, or the number formatted ("" when absent or NaN,
  // "inf" and "-inf" for infinities; "" for a job that is not ok).
  std::string cell(const record::JobRecord& r) const;
};

// In table order: scene, resolution, technique, status, the figures, reason.
const std::vector<ReportColumn>& report_columns();
// The column called `name`; throws std::out_of_range for another name.
const ReportColumn& report_column(const std::string& name);
// The columns of one (scene, resolution) table of `records`: not the
// per-group ones, nor optional ones that no record fills.
std::vector<const ReportColumn*> group_table_columns(const std::vector<record::JobRecord>& records);

// "exact (exact_clipper)" or "Monte Carlo, 256 spp (embree_stratified_packet16)",
// and why an exact reference asked for is Monte Carlo.
std::string reference_label(const record::ReferenceRecord& r);

}  // namespace sb::results
