// The paper tables and pgfplots CSVs of `report --latex` (no TeX needed):
// which cells are bold, the escaping of names, the headers' units, the
// numbers' digits, the CSV's rows, and the driver's refusal of an unknown
// column (exit 2, naming it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "../metrics/test_util.h"
#include "core/error.h"
#include "latex_fixture.h"
#include "results/latex_export.h"
#include "results/latex_tables.h"
#include "results/pgf_csv.h"

namespace sb {

using record::JobRecord;
using results::latex_columns;
using results::latex_number;
using results::latex_text;
using results::LatexFiles;
using results::make_error_time_csv;
using results::make_latex_table;
using results::write_latex;

namespace {

std::vector<const JobRecord*> pointers(const std::vector<JobRecord>& records) {
  std::vector<const JobRecord*> out;
  out.reserve(records.size());
  for (const auto& r : records) out.push_back(&r);
  return out;
}

// The table's body rows (between \midrule and \bottomrule), one string each.
std::vector<std::string> body_rows(const std::string& table) {
  const size_t begin = table.find("\\midrule\n") + 9, end = table.find("\\bottomrule");
  std::vector<std::string> rows;
  std::istringstream in(table.substr(begin, end - begin));
  for (std::string line; std::getline(in, line);) rows.push_back(line);
  return rows;
}

std::string table_of(const std::vector<JobRecord>& records, const std::vector<std::string>& cols) {
  return make_latex_table(pointers(records), latex_columns(cols, records));
}

}  // namespace

TEST(LatexTables, BestValuePerColumnIsBoldWithTiesAndDirection) {
  const auto records = test::latex_records();
  const std::string table = table_of(records, {});  // the default columns
  const auto rows = body_rows(table);
  ASSERT_EQ(rows.size(), 5U) << table;
  // frame_ms (lower), rmse (lower, a tie), penumbra_rmse (lower), ssim (higher);
  // x_control is left out: no record has a control.
  EXPECT_EQ(rows[0], "none & \\textbf{2.50} & 0.250 & 0.500 & 0.410 \\\\");
  EXPECT_EQ(rows[1], "pcf\\_box/k=3,size=1024 & 9.00 & \\textbf{0.0123} & 0.0310 & 0.930 \\\\");
  EXPECT_EQ(rows[2], latex_text(test::kNastyTechnique) +
                         " & 12.0 & \\textbf{0.0123} & \\textbf{0.0299} & \\textbf{0.970} \\\\");
  // Not ok: the status across the figures, and the failed job's better
  // numbers neither shown nor bold.
  EXPECT_EQ(rows[3], "shadow\\_volume/mode=zpass & \\multicolumn{4}{l}{\\emph{skipped}} \\\\");
  EXPECT_EQ(rows[4], "vsm/k=9,prefilter=gauss & \\multicolumn{4}{l}{\\emph{failed}} \\\\");
}

// With `none` the jobs' timing control, as in a run: it is marked, and the
// fastest competitor is bold, not the control.
TEST(LatexTables, TheTimingControlIsMarkedAndNeverBold) {
  auto records = test::latex_records();
  for (auto& r : records) {
    if (!r.timing) continue;
    r.timing->control = record::ControlTiming{};
    r.timing->control->technique = "none";
    r.timing->control->frame = r.timing->frame;
    r.timing->control->frame_ratio = r.timing->frame;  // any ratio: this test reads frame_ms
  }
  const auto rows = body_rows(table_of(records, {"frame_ms", "rmse"}));
  ASSERT_EQ(rows.size(), 5U);
  EXPECT_EQ(rows[0], "none \\emph{(control)} & 2.50 & 0.250 \\\\");
  EXPECT_EQ(rows[1], "pcf\\_box/k=3,size=1024 & \\textbf{9.00} & \\textbf{0.0123} \\\\");
}

TEST(LatexTables, InfinitePsnrIsBestAndPrintedAsInfinity) {
  const auto records = test::latex_records();
  const auto rows = body_rows(table_of(records, {"psnr", "status"}));
  ASSERT_EQ(rows.size(), 5U);
  EXPECT_EQ(rows[0], "none & 12.0 & ok \\\\");
  EXPECT_EQ(rows[1], "pcf\\_box/k=3,size=1024 & 38.2 & ok \\\\");
  EXPECT_NE(rows[2].find("& \\textbf{\\boldmath$\\infty$} & ok"), std::string::npos) << rows[2];
}

TEST(LatexTables, InfinityIsNeverTheLowestError) {
  auto records = test::latex_records();
  records.resize(2);
  records[0].metrics->visibility.geometry->rmse = std::numeric_limits<double>::infinity();
  const auto rows = body_rows(table_of(records, {"rmse"}));
  EXPECT_EQ(rows[0], "none & $\\infty$ \\\\");
  EXPECT_EQ(rows[1], "pcf\\_box/k=3,size=1024 & \\textbf{0.0123} \\\\");
}

TEST(LatexTables, HeadersCarryLabelsAndUnits) {
  const auto records = test::latex_records();
  const std::string table =
      table_of(records, {"frame_ms", "technique_ms", "psnr", "ssim", "frac_over_0.05"});
  EXPECT_NE(table.find("\\begin{tabular}{lrrrrr}\n\\toprule\nTechnique & Frame (ms) & "
                       "Technique (ms) & PSNR (dB) & SSIM & Error \\textgreater{} 0.05 \\\\\n"
                       "\\midrule\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("\\bottomrule\n\\end{tabular}\n"), std::string::npos);
}

TEST(LatexTables, SpecialCharactersAreEscaped) {
  EXPECT_EQ(latex_text("a_b&c%d#e{f}g~h^i\\j$k<l>m|n\no"),
            "a\\_b\\&c\\%d\\#e\\{f\\}g\\textasciitilde{}h\\textasciicircum{}i\\textbackslash{}"
            "j\\ensuremath{\\$}k\\textless{}l\\textgreater{}m\\textbar{}n o");
  EXPECT_EQ(latex_text("pcf_box/k=3,size=1024"), "pcf\\_box/k=3,size=1024");
}

// Outside ASCII: the Latin letters pdflatex sets in its default encoding stay
// UTF-8; other characters print as their code points, and bytes that are
// not UTF-8 (a cut character, an overlong form, a surrogate) as U+FFFD.
TEST(LatexTables, NonAsciiTextKeepsLatinLettersAndShowsOthersAsCodePoints) {
  EXPECT_EQ(latex_text("Café Erdős Dvořák"), "Café Erdős Dvořák");
  EXPECT_EQ(latex_text("σκιά"),
            "\\textless{}U+03C3\\textgreater{}\\textless{}U+03BA\\textgreater{}"
            "\\textless{}U+03B9\\textgreater{}\\textless{}U+03AC\\textgreater{}");
  EXPECT_EQ(latex_text("影_1"), "\\textless{}U+5F71\\textgreater{}\\_1");
  EXPECT_EQ(latex_text("\xF0\x9F\x98\x80"), "\\textless{}U+1F600\\textgreater{}");
  EXPECT_EQ(latex_text("Þ×"), "\\textless{}U+00DE\\textgreater{}\\textless{}U+00D7\\textgreater{}");
  const std::string fffd = "\\textless{}U+FFFD\\textgreater{}";
  EXPECT_EQ(latex_text("a\xC3"), "a" + fffd);                 // cut after its first byte
  EXPECT_EQ(latex_text("\xC0\xAF"), fffd + fffd);             // overlong '/'
  EXPECT_EQ(latex_text("\xED\xA0\x80"), fffd + fffd + fffd);  // a surrogate
  EXPECT_EQ(latex_text("\xFFx"), fffd + "x");
}

TEST(LatexTables, NumbersHaveFixedSignificantDigits) {
  EXPECT_EQ(latex_number(2.5), "2.50");
  EXPECT_EQ(latex_number(0.012345), "0.0123");
  EXPECT_EQ(latex_number(123.45), "123");
  EXPECT_EQ(latex_number(1234.5), "1230");
  EXPECT_EQ(latex_number(9.996), "10.0");
  EXPECT_EQ(latex_number(0.0), "0");
  EXPECT_EQ(latex_number(-0.5), "$-$0.500");
  EXPECT_EQ(latex_number(0.00001234), "$1.23\\times10^{-5}$");
  EXPECT_EQ(latex_number(std::nan("")), "--");
  EXPECT_EQ(latex_number(std::numeric_limits<double>::infinity()), "$\\infty$");
  EXPECT_EQ(latex_number(0.012345, 2), "0.012");
}

TEST(LatexTables, UnknownColumnIsRefusedNamingItAndTheValidOnes) {
  const auto records = test::latex_records();
  try {
    latex_columns({"frame_ms", "fps"}, records);
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "--latex-columns");
    EXPECT_NE(e.problem().find("\"fps\""), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find("penumbra_rmse"), std::string::npos) << e.what();
  }
  EXPECT_THROW(latex_columns({"scene"}, records), core::InputError);  // a group, not a column
}

TEST(PgfCsv, RowsByTimeWithBracedNamesAndTheParetoFront) {
  const auto records = test::latex_records();
  const std::string csv = make_error_time_csv(pointers(records), "visibility.geometry.rmse");
  std::istringstream in(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4U) << csv;  // ok jobs only
  EXPECT_EQ(lines[0], "technique,time_ms,time_p10_ms,time_p90_ms,error,pareto,control");
  EXPECT_EQ(lines[1].rfind("{none},2.5,", 0), 0U) << lines[1];
  EXPECT_EQ(lines[1].substr(lines[1].size() - 9), ",0.25,1,0");
  EXPECT_EQ(lines[2].rfind("{pcf\\_box/k=3,size=1024},9,", 0), 0U) << lines[2];
  EXPECT_EQ(lines[2].substr(lines[2].size() - 11), ",0.0123,1,0");
  // As accurate as pcf_box and slower: dominated.
  EXPECT_EQ(lines[3].rfind("{" + latex_text(test::kNastyTechnique) + "},12,", 0), 0U) << lines[3];
  EXPECT_EQ(lines[3].substr(lines[3].size() - 11), ",0.0123,0,0");
  // Higher is better for SSIM: the slowest is on the front too.
  const std::string ssim = make_error_time_csv(pointers(records), "visibility.geometry.ssim");
  EXPECT_NE(ssim.find(",0.97,1,0\n"), std::string::npos) << ssim;
}

TEST(LatexExport, OneTableAndCsvPerGroupAndADocumentThatInputsThem) {
  test::TempDir dir("latex_export");
  auto records = test::latex_records("plates/layout=edge", "64x48");
  for (const auto& r : test::latex_records("jeep/count=1", "96x72")) records.push_back(r);
  const LatexFiles files = write_latex(records, dir.file("latex"));
  ASSERT_EQ(files.tables.size(), 2U);
  ASSERT_EQ(files.csvs.size(), 2U);
  EXPECT_EQ(files.tables[0], dir.file("latex/table-plates-layout-edge-64x48.tex"));
  EXPECT_EQ(files.csvs[1], dir.file("latex/error-time-jeep-count-1-96x72.csv"));
  const std::string doc = test::read_text(files.document);
  EXPECT_NE(doc.find("\\usepackage{booktabs}"), std::string::npos);
  EXPECT_NE(doc.find("\\input{table-plates-layout-edge-64x48.tex}"), std::string::npos);
  EXPECT_NE(doc.find("\\input{table-jeep-count-1-96x72.tex}"), std::string::npos);
  // Each point its own plot, with its p10-p90 bars and legend entry.
  for (const char* part :
       {"  {error-time-jeep-count-1-96x72.csv};\n\\addlegendentry{none}\n",
        "x error plus expr=\\thisrow{time_p90_ms}-\\thisrow{time_ms}",
        "x error minus expr=\\thisrow{time_ms}-\\thisrow{time_p10_ms}",
        "\\addlegendentry{Pareto front}", "\\sbfit{\\input{table-jeep-count-1-96x72.tex}}"})
    EXPECT_NE(doc.find(part), std::string::npos) << part << "\n" << doc;
  EXPECT_EQ(test::read_text(files.tables[0]), table_of(test::latex_records(), {}));
}

TEST(LatexCli, ReportLatexWritesTheFilesAndRefusesAnUnknownColumn) {
  const auto dir = test::test_folder("sb_latex_cli_");
  test::write_run(dir / "run", test::latex_records());
  const std::string run = "'" SHADOWBENCH_EXE "' report '" + (dir / "run").string() + "'";

  const test::CliRun bad = test::run_command(run + " --latex --latex-columns frame_ms,fps");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--latex-columns"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("\"fps\""), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("penumbra_rmse"), std::string::npos) << bad.output;  // the valid ones
  EXPECT_FALSE(std::filesystem::exists(dir / "run" / "report")) << "wrote before refusing";

  const test::CliRun ok = test::run_command(run + " --latex --latex-columns frame_ms,psnr --out '" +
                                            (dir / "out").string() + "'");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const auto latex = dir / "out" / "latex";
  EXPECT_NE(ok.output.find("latex: " + (latex / "tables.tex").string()), std::string::npos)
      << ok.output;
  const std::string table =
      test::read_text((latex / "table-plates-layout-edge-64x48.tex").string());
  EXPECT_NE(table.find("Technique & Frame (ms) & PSNR (dB) \\\\"), std::string::npos) << table;
  EXPECT_TRUE(std::filesystem::exists(latex / "error-time-plates-layout-edge-64x48.csv"));
  std::filesystem::remove_all(dir);
}

}  // namespace sb
