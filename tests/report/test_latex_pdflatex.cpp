// `report --latex` as a paper's author uses it: pdflatex compiles tables.tex
// (every table and pgfplots figure), poppler renders the page and reads its
// text back; and `report --style paper` draws charts as vector PDFs one
// column (3.3 in) wide.
//
// These tests FAIL, not skip, without their oracles (pdflatex with
// booktabs and pgfplots, poppler-utils): "report --latex output compiles
// with pdflatex" is what they stand for, and a test that passes without
// checking it would say so falsely. scripts/install-deps.sh --test installs
// them (texlive-latex-base, texlive-latex-recommended, texlive-pictures,
// poppler-utils).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "../results/control_run.h"
#include "core/image.h"
#include "latex_fixture.h"
#include "metrics/image_io.h"
#include "results/charts.h"
#include "results/latex_export.h"
#include "results/latex_tables.h"

namespace sb {

using test::CliRun;
using test::run_command;

namespace {

namespace fs = std::filesystem;

constexpr const char* kInstall = "install TeX Live and poppler: scripts/install-deps.sh --test";

// Fails the test when `tool` is not on PATH.
::testing::AssertionResult on_path(const std::string& tool) {
  if (run_command("command -v " + tool).exit_code == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << tool << " is missing: " << kInstall;
}

// Pixels of an image darker than near-white.
long inked_pixels(const core::ImageF& img) {
  long n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y, 0) < 0.8f || img.at(x, y, 1) < 0.8f || img.at(x, y, 2) < 0.8f) ++n;
  return n;
}

// "Page size:       237.6 x 203.76 pts" of pdfinfo: the width in points.
double page_width_pt(const CliRun& info) {
  const size_t at = info.output.find("Page size:");
  if (at == std::string::npos) return 0.0;
  return std::stod(info.output.substr(info.output.find_first_of("0123456789", at)));
}

// A word of `pdftotext -bbox-layout`, in points from the page's top left.
struct Word {
  int page = 0;
  double page_width = 0;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::string text;
};

std::vector<Word> pdf_words(const std::string& xhtml) {
  std::vector<Word> out;
  int page = 0;
  double page_width = 0;
  const std::regex token(
      "<page width=\"([0-9.]+)\"|<word xMin=\"([0-9.]+)\" yMin=\"([0-9.]+)\" xMax=\"([0-9.]+)\" "
      "yMax=\"([0-9.]+)\">([^<]*)</word>");
  for (std::sregex_iterator it(xhtml.begin(), xhtml.end(), token), end; it != end; ++it) {
    if ((*it)[1].length() > 0) {
      ++page;
      page_width = std::stod((*it)[1]);
      continue;
    }
    out.push_back({page, page_width, std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4]),
                   std::stod((*it)[5]), (*it)[6]});
  }
  return out;
}

// The widest "Overfull \hbox (X pt too wide)" of a LaTeX log, 0 without one.
double widest_overfull_pt(const std::string& log) {
  double widest = 0;
  const std::regex overfull("Overfull \\\\hbox \\(([0-9.]+)pt too wide\\)");
  for (std::sregex_iterator it(log.begin(), log.end(), overfull), end; it != end; ++it)
    widest = std::max(widest, std::stod((*it)[1]));
  return widest;
}

}  // namespace

// The issue-61 page: a run as configs/ci.json makes one (five techniques
// with long names beside the control `none`, nine columns) set with
// tables.tex's own page (letter paper, 2 cm margins: text from 56.9 pt to
// 555.1 pt).
// Its tables overflowed the text by 53-58 pt and the figure's point labels
// lay on each other. Now: no overfull box wider than 1 pt in the log, every
// word of the PDF inside the text width, and no two words' boxes on a page
// overlapping (legend entries, ticks, table cells, captions).
TEST(LatexPdflatex, TablesFitTheTextWidthAndNoLabelsOverlap) {
  ASSERT_TRUE(on_path("pdflatex"));
  ASSERT_TRUE(on_path("pdftotext"));
  const fs::path dir = test::test_folder("sb_latex_fit_");
  auto records = test::control_run_records();
  for (const auto& r : test::control_run_records(0.3, "foliage/count=200,spread=1.5", "640x480"))
    records.push_back(r);
  records.back().timing = records[records.size() - 3].timing;  // a tie: pcss's frames

  results::LatexOptions options;  // the default columns and three more a paper may want
  options.columns = {"frame_ms",      "technique_ms", "x_control", "rmse", "mae",
                     "penumbra_rmse", "psnr",         "ssim",      "flip"};
  results::write_latex(records, (dir / "latex").string(), options);
  const CliRun tex = run_command("cd '" + (dir / "latex").string() +
                                 "' && pdflatex -interaction=nonstopmode -halt-on-error "
                                 "tables.tex");
  ASSERT_EQ(tex.exit_code, 0) << tex.output;
  const std::string log = test::read_text((dir / "latex" / "tables.log").string());
  EXPECT_LE(widest_overfull_pt(log), 1.0) << log;

  const fs::path pdf = dir / "latex" / "tables.pdf";
  // The rankings are set, the tie with its sign.
  const CliRun text = run_command("pdftotext -layout '" + pdf.string() + "' -");
  EXPECT_NE(text.output.find("Ranking by time: foliage/count=200,spread=1.5 @ 640x480"),
            std::string::npos)
      << text.output;
  EXPECT_TRUE(std::regex_search(text.output, std::regex("\n +4 ?\u2248 +shadow"))) << text.output;
  const CliRun box = run_command("pdftotext -bbox-layout '" + pdf.string() + "' -");
  ASSERT_EQ(box.exit_code, 0) << box.output;
  const std::vector<Word> words = pdf_words(box.output);
  ASSERT_GT(words.size(), 100U) << box.output;
  constexpr double kMargin = 2 / 2.54 * 72, kSlack = 0.5;  // 2 cm in PDF points
  for (const Word& w : words)
    EXPECT_TRUE(w.x0 >= kMargin - kSlack && w.x1 <= w.page_width - kMargin + kSlack)
        << "\"" << w.text << "\" on page " << w.page << " spans " << w.x0 << "-" << w.x1
        << " pt, outside the text's " << kMargin << "-" << w.page_width - kMargin;
  // Boxes that share more than half a point both ways overlap (a word's
  // box is its font's height, so lines set tight may touch).
  for (size_t i = 0; i < words.size(); ++i)
    for (size_t j = i + 1; j < words.size(); ++j) {
      const Word &a = words[i], &b = words[j];
      if (a.page != b.page) continue;
      const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
      const double h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
      EXPECT_FALSE(w > 0.5 && h > 0.5)
          << "\"" << a.text << "\" and \"" << b.text << "\" overlap on page " << a.page << " (" << w
          << " x " << h << " pt)";
    }
  if (!HasFailure() && !std::getenv("SB_KEEP")) fs::remove_all(dir);  // else kept, to look at
}

TEST(LatexPdflatex, TablesAndPlotsCompileAndTheFirstPageRenders) {
  ASSERT_TRUE(on_path("pdflatex"));
  ASSERT_TRUE(on_path("pdftoppm"));
  ASSERT_TRUE(on_path("pdftotext"));
  const fs::path dir = test::test_folder("sb_latex_pdflatex_");
  auto records = test::latex_records("plates/layout=edge", "64x48");
  for (const auto& r : test::latex_records("jeep/count=1", "96x72")) records.push_back(r);
  results::LatexOptions options;
  options.columns = {"frame_ms", "rmse", "penumbra_rmse", "psnr", "ssim"};
  options.title = "synthetic_run & co";
  const auto files = results::write_latex(records, (dir / "latex").string(), options);

  const CliRun tex = run_command("cd '" + (dir / "latex").string() +
                                 "' && pdflatex -interaction=nonstopmode -halt-on-error "
                                 "tables.tex");
  ASSERT_EQ(tex.exit_code, 0) << tex.output;
  const fs::path pdf = dir / "latex" / "tables.pdf";
  ASSERT_TRUE(fs::exists(pdf));

  const CliRun png = run_command("pdftoppm -r 50 -png -f 1 -l 1 '" + pdf.string() + "' '" +
                                 (dir / "page").string() + "'");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  fs::path page;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("page", 0) == 0) page = e.path();
  ASSERT_FALSE(page.empty()) << "pdftoppm wrote no page";
  const core::ImageF img = metrics::io::read_image(page.string());
  // A4 at 50 dpi is 413 x 585 px; two tables and a plot ink thousands.
  EXPECT_GT(inked_pixels(img), 2000) << "page 1 is (nearly) blank: " << page;

  const CliRun text = run_command("pdftotext -layout '" + pdf.string() + "' -");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("Technique"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("vsm/k=9,prefilter=gauss"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("Frame (ms)"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("plates/layout=edge @ 64x48"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("a&b=50%,c#d={x}"), std::string::npos)  // the nasty name, as itself
      << text.output;
  // The bold cells are in the tables that were compiled.
  EXPECT_NE(test::read_text(files.tables[0]).find("\\textbf{2.50}"), std::string::npos);
  // Bold Computer Modern at the tables' \small size is in the PDF: the best
  // values were set; and no bitmap (Type 3) font stands in for a character.
  const CliRun fonts = run_command("pdffonts '" + pdf.string() + "'");
  EXPECT_NE(fonts.output.find("CMBX9"), std::string::npos) << fonts.output;
  EXPECT_EQ(fonts.output.find("Type 3"), std::string::npos) << fonts.output;
  fs::remove_all(dir);
}

// Labels in several scripts (configs allow any UTF-8): tables.tex compiles,
// the Latin letters read back as themselves, the others as their code points
// (docs/paper.md), and no bitmap font stands in. One label holds every
// letter latex_text passes through as UTF-8.
TEST(LatexPdflatex, NonAsciiLabelsCompileAndReadBack) {
  ASSERT_TRUE(on_path("pdflatex"));
  ASSERT_TRUE(on_path("pdftotext"));
  ASSERT_TRUE(on_path("pdffonts"));
  const fs::path dir = test::test_folder("sb_latex_non_ascii_");
  std::string every_letter;
  for (char32_t c = 0xC0; c <= 0x17E; ++c) {
    const std::string one{char(0xC0 | (c >> 6)), char(0x80 | (c & 0x3F))};  // two-byte UTF-8
    if (results::latex_text(one) == one) every_letter += one;
  }
  ASSERT_GT(every_letter.size(), 2 * 150U);  // 165 letters
  auto records = test::latex_records("plates/layout=edge", "64x48");
  records[0].technique_variant = "Café Ångström Erdős Dvořák";
  records[1].technique_variant = "σκιά";
  records[2].technique_variant = "影子";
  records[3].technique_variant = "тень";
  records[4].technique_variant = every_letter;
  for (const auto& r : test::latex_records("σκηνή/étage=1", "64x48")) records.push_back(r);
  results::LatexOptions options;
  options.columns = {"frame_ms", "rmse"};
  options.title = "Résumé";
  results::write_latex(records, (dir / "latex").string(), options);
  const CliRun tex = run_command("cd '" + (dir / "latex").string() +
                                 "' && pdflatex -interaction=nonstopmode -halt-on-error "
                                 "tables.tex");
  ASSERT_EQ(tex.exit_code, 0) << tex.output;
  const fs::path pdf = dir / "latex" / "tables.pdf";
  // pdftotext writes an accented letter as the letter and a combining
  // accent (NFD); composed again (NFC) it is the label's own character.
  const CliRun text =
      run_command("pdftotext '" + pdf.string() + "' '" + (dir / "tables.txt").string() +
                  "' && python3 -c 'import sys, unicodedata; "
                  "sys.stdout.write(unicodedata.normalize(\"NFC\", sys.stdin.read()))' < '" +
                  (dir / "tables.txt").string() + "'");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* shown :
       {"Café Ångström Erdős Dvořák", "Résumé", "<U+03C3><U+03BA><U+03B9><U+03AC>",
        "<U+5F71><U+5B50>", "<U+0442><U+0435><U+043D><U+044C>",
        "<U+03C3><U+03BA><U+03B7><U+03BD><U+03AE>/étage=1 @ 64x48"})
    EXPECT_NE(text.output.find(shown), std::string::npos) << shown << "\n" << text.output;
  const CliRun fonts = run_command("pdffonts '" + pdf.string() + "'");
  EXPECT_EQ(fonts.output.find("Type 3"), std::string::npos) << fonts.output;
  fs::remove_all(dir);
}

TEST(LatexPdflatex, PaperStyleChartsAreVectorPdfsOneColumnWide) {
  ASSERT_TRUE(on_path("pdfinfo"));
  if (const std::string why = results::charts_unavailable_reason(); !why.empty())
    FAIL() << "charts cannot be drawn here: " << why;
  const fs::path dir = test::test_folder("sb_latex_paper_");
  results::ChartOptions options;
  options.style = "paper";
  const auto charts = results::write_charts(test::latex_records(), (dir / "out").string(), options);
  ASSERT_FALSE(charts.empty());
  for (const auto& c : charts) {
    ASSERT_FALSE(c.pdf.empty()) << c.kind;
    ASSERT_TRUE(fs::exists(c.pdf)) << c.pdf;
    EXPECT_TRUE(fs::exists(c.svg) && fs::exists(c.png)) << c.svg;
    const CliRun info = run_command("pdfinfo '" + c.pdf + "'");
    ASSERT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NEAR(page_width_pt(info), 3.3 * 72.0, 0.5) << c.pdf << "\n" << info.output;
    // Vector: no raster image anywhere in the file, and the fonts embedded
    // as TrueType (no Type 3), Computer Modern among them.
    const std::string bytes = test::read_text(c.pdf);
    EXPECT_EQ(bytes.find("/Subtype /Image"), std::string::npos)
        << c.pdf << " embeds a raster image";
    if (c.kind == "error_time") {  // its markers are vector forms
      EXPECT_NE(bytes.find("/Subtype /Form"), std::string::npos) << c.pdf;
    }
    const CliRun fonts = run_command("pdffonts '" + c.pdf + "'");
    EXPECT_NE(fonts.output.find("Cmr10"), std::string::npos) << fonts.output;
    EXPECT_EQ(fonts.output.find("Type 3"), std::string::npos) << fonts.output;
  }
  // The default style writes no PDF.
  const auto plain = results::write_charts(test::latex_records(), (dir / "plain").string(), {});
  ASSERT_FALSE(plain.empty());
  EXPECT_TRUE(plain[0].pdf.empty());
  EXPECT_FALSE(fs::exists(fs::path(plain[0].svg).replace_extension(".pdf")));
  fs::remove_all(dir);
}

}  // namespace sb
