#pragma once
// Paper tables: one booktabs tabular per (scene variant, resolution) of a
// run's records, as a .tex fragment that needs \usepackage{booktabs} and
// nothing else (`report --latex`, docs/paper.md). Columns come from
// report_columns(): the technique first, then the chosen ones, each headed
// by its label and unit ("Frame (ms)").
//
//  - Numbers are printed to a fixed number of significant digits (3 by
//    default); below 1e-4 as a power of ten; +inf as $\infty$; absent or NaN
//    as "--".
//  - The best value of each column that improves one way (ReportColumn::better)
//    is set in \textbf: the lowest time or error, the highest PSNR or SSIM.
//    Values are compared as printed, so every row that prints the best value
//    is bold (ties). Only ok jobs compete, only finite values win, except
//    +inf where higher is better (an exact match's PSNR). A column with a
//    value in fewer than two rows has no bold. The timing control (config
//    `frames.control`, "none" by default, named by the jobs' records) is a
//    baseline, not a competitor: its row is marked "(control)" and never
//    bold, although it is the fastest.
//  - A job that was not ok shows its status across the figures (no bold).
//  - Text from records is escaped: every LaTeX special character prints as
//    itself (latex_text).
#include <string>
#include <vector>

#include "record/job_record.h"
#include "results/report_columns.h"

namespace sb::results {

// The columns shown when --latex-columns is not given; those no record fills
// are left out.
const std::vector<std::string>& default_latex_columns();

// The columns called `names` (report column names, not per group; the
// technique is always the first column and is not named). Throws InputError
// at "--latex-columns" for an unknown name, naming it and the valid ones.
// Empty `names`: the default columns that some record of `records` fills.
std::vector<const ReportColumn*> latex_columns(const std::vector<std::string>& names,
                                               const std::vector<record::JobRecord>& records);

// `s` as LaTeX text that prints `s`: _ & % # { } ~ ^ \ $ < > | escaped,
// line breaks as spaces. Outside ASCII, the Latin letters pdflatex sets in
// its default encoding (é, ñ, ő, ł, ...) stay UTF-8; every other character
// (Greek, Cyrillic, CJK, signs) prints as its code point, "<U+03B1>", and
// bytes that are not UTF-8 as "<U+FFFD>" (docs/paper.md).
std::string latex_text(const std::string& s);

// `v` to `digits` significant digits as LaTeX: "12.3", "0.0123", "1235",
// "$1.23\times10^{-5}$", "$-$0.5", "$\infty$"; "--" for NaN.
std::string latex_number(double v, int digits = 3);

// The tabular of one group's records (in their order), with a comment
// naming the group.
std::string make_latex_table(const std::vector<const record::JobRecord*>& group,
                             const std::vector<const ReportColumn*>& columns, int digits = 3);

}  // namespace sb::results
