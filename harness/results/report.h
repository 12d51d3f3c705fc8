#pragma once
// Tables made from a run's records: results.csv and summary.md, one row per
// technique variant, grouped by scene variant and resolution in summary.md.
// Their columns are report_columns() (results/report_columns.h).
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// Text from records (labels, reasons) inside a Markdown table or heading:
// the characters that end a cell, open code, links, emphasis, HTML or an
// entity are escaped, line breaks become spaces, and the text is cut and its
// control characters escaped by core::bounded_text (core::kMessageChars), so a
// label cannot break the table, inject markup or drive a terminal.
std::string markdown_text(const std::string& s);

std::string make_csv(const std::vector<record::JobRecord>& records);
std::string make_markdown(const std::vector<record::JobRecord>& records, const std::string& title);
// Writes results.csv and summary.md into run_dir (atomically).
void write_reports(const std::string& run_dir, const std::vector<record::JobRecord>& records,
                   const std::string& title);

}  // namespace sb::results
