// A failed job carries no numbers: a technique that
// writes NaN, inf and V outside [0, 1] fails its visibility check, and
// `run`'s stdout, summary.md, results.csv, the HTML report and the charts'
// data show its status and reason only; its record keeps what it measured
// under "partial", and invalid.png marks exactly the offending pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../config/cli_runner.h"
#include "core/error.h"
#include "e2e_util.h"
#include "invalid_visibility_rects.h"
#include "metrics/image_io.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kW = 40, kH = 30;
constexpr const char* kFailed = "writes_invalid";

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The cells of a Markdown table row "| a | b |", trimmed.
std::vector<std::string> markdown_cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  for (size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|') {
      const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return cells;
}

// The fields of one CSV line (quoted fields with "" for a quote).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

// Every Markdown table row of `text` for `technique`: its cells other than
// technique, status and reason are the figures. Returns how many rows.
int expect_markdown_rows_without_figures(const std::string& text, const std::string& where) {
  int rows = 0;
  std::vector<std::string> header;
  for (const std::string& line : lines_of(text)) {
    if (line.rfind("| technique", 0) == 0) header = markdown_cells(line);
    if (line.rfind("| " + std::string(kFailed) + " ", 0) != 0) continue;
    ++rows;
    const auto cells = markdown_cells(line);
    EXPECT_EQ(cells.size(), header.size()) << where << ": " << line;
    if (cells.size() != header.size()) continue;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (header[i] == "technique" || header[i] == "status" || header[i] == "reason") continue;
      EXPECT_EQ(cells[i], "") << where << ": column " << header[i] << " of " << line;
    }
    EXPECT_EQ(cells[1], "failed") << where << ": " << line;
  }
  return rows;
}

// The offending pixels by kind, as the plugin writes them: 1 NaN/inf,
// 2 below 0, 3 above 1, 0 valid; row 0 at the top, as in image files.
std::vector<int> expected_kinds() {
  std::vector<int> kinds(size_t(kW) * kH, 0);
  for (const InvalidRect& r : kInvalidRects) {
    const int kind = !std::isfinite(r.value) ? 1 : r.value < 0 ? 2 : r.value > 1.0001f ? 3 : 0;
    for (int y = r.y; y < r.y + r.h; ++y)
      for (int x = r.x; x < r.x + r.w; ++x) kinds[size_t(kH - 1 - y) * kW + x] = kind;
  }
  return kinds;
}

TEST(FailedJobs, CarryNoNumbersInAnyTableAndMarkTheirInvalidPixels) {
  const fs::path dir = fresh_test_folder("failed_jobs");
  const json config = {{"name", "failed_jobs"},
                       {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                       {"techniques", {kFailed, "shadow_map"}},
                       {"resolutions", {{kW, kH}}},
                       {"frames", {{"warmup", 0}, {"timed", 2}}},
                       {"reference", {{"spp", 4}}}};
  const std::string file = (dir / "failed.json").string();
  std::ofstream(file) << config.dump();
  const fs::path run_dir = dir / "run";
  // The shipped plugins and, besides them, the test's.
  ::setenv("SHADOWBENCH_PLUGIN_PATH", INVALID_VISIBILITY_PLUGIN_DIR, 1);
  const CliResult run = run_cli("run " + file + " --no-cache --out " + run_dir.string(), false);
  const CliResult report =
      run_cli("report " + run_dir.string() + " --out " + (dir / "report").string());
  ::unsetenv("SHADOWBENCH_PLUGIN_PATH");
  ASSERT_EQ(run.exit_code, core::kExitJobsFailed) << run.output;
  ASSERT_EQ(report.exit_code, 0) << report.output;

  json rec, ok;
  for (const std::string& line : lines_of(slurp(run_dir / "results.jsonl"))) {
    json r = json::parse(line);
    (r["technique_variant"] == kFailed ? rec : ok) = std::move(r);
  }
  const std::string job_dir = "jobs/" + rec["job_id"].get<std::string>();
  ASSERT_EQ(rec["status"], "failed") << rec.dump();
  ASSERT_EQ(ok["status"], "ok") << ok.dump();

  // stdout: the job's line names the reason, the table no figure.
  bool job_line = false;
  for (const std::string& line : lines_of(run.output))
    if (line.find(std::string(" ") + kFailed + ": failed (") != std::string::npos) {
      job_line = true;
      EXPECT_EQ(line.find("ms"), std::string::npos) << line;
      EXPECT_EQ(line.find("RMSE"), std::string::npos) << line;
    }
  EXPECT_TRUE(job_line) << run.output;
  EXPECT_EQ(expect_markdown_rows_without_figures(run.output, "stdout"), 1) << run.output;
  const std::string summary = slurp(run_dir / "summary.md");
  EXPECT_EQ(expect_markdown_rows_without_figures(summary, "summary.md"), 1) << summary;

  // results.csv: every column but the names, status and reason empty.
  const auto csv = lines_of(slurp(run_dir / "results.csv"));
  ASSERT_EQ(csv.size(), 3u);
  const auto header = csv_fields(csv[0]);
  int failed_rows = 0, ok_figures = 0;
  for (size_t l = 1; l < csv.size(); ++l) {
    const auto row = csv_fields(csv[l]);
    ASSERT_EQ(row.size(), header.size()) << csv[l];
    for (size_t i = 0; i < row.size(); ++i) {
      const std::string& h = header[i];
      if (h == "scene" || h == "resolution" || h == "technique" || h == "status" || h == "reason")
        continue;
      if (row[2] == kFailed)
        EXPECT_EQ(row[i], "") << "results.csv column " << h << ": " << csv[l];
      else if (!row[i].empty())
        ++ok_figures;
    }
    failed_rows += row[2] == kFailed;
  }
  EXPECT_EQ(failed_rows, 1);
  EXPECT_GT(ok_figures, 5);

  // The HTML report: the summary row's figure cells and the card's figures empty.
  const std::string html = slurp(dir / "report" / "index.html");
  size_t rows = 0;
  for (size_t at = html.find("<tr"); at != std::string::npos; at = html.find("<tr", at + 1)) {
    const std::string row = html.substr(at, html.find("</tr>", at) - at);
    if (row.find(">" + std::string(kFailed) + "<") == std::string::npos) continue;
    ++rows;
    for (size_t c = row.find("<td class=\"num\">"); c != std::string::npos;
         c = row.find("<td class=\"num\">", c + 1))
      EXPECT_EQ(row.compare(c, 21, "<td class=\"num\"></td>"), 0) << row;
  }
  EXPECT_EQ(rows, 1u) << html;
  const size_t card = html.find("<span class=\"name\">" + std::string(kFailed) + "</span>");
  ASSERT_NE(card, std::string::npos);
  const size_t nums = html.find("<span class=\"nums\">", card);
  ASSERT_NE(nums, std::string::npos);
  EXPECT_EQ(html.compare(nums, 26, "<span class=\"nums\"></span>"), 0) << html.substr(nums, 200);
  EXPECT_NE(html.find(job_dir + "/invalid.png"), std::string::npos);

  // The charts' data: no point, series or listing of the failed job.
  int charts = 0;
  for (const auto& entry : fs::directory_iterator(dir / "report")) {
    if (entry.path().extension() != ".json") continue;
    ++charts;
    const std::string data = slurp(entry.path());
    EXPECT_EQ(data.find(kFailed), std::string::npos) << entry.path() << ": " << data;
  }
  EXPECT_GT(charts, 0);

  // The record: failed for its V, its figures under "partial" only.
  EXPECT_NE(rec["reason"].get<std::string>().find("visibility outside [0,1]"), std::string::npos);
  for (const char* key : {"metrics", "timing", "classes", "second_reference"})
    EXPECT_FALSE(rec.contains(key)) << key << " in " << rec.dump();
  EXPECT_FALSE(rec["technique"].contains("gpu_bytes")) << rec.dump();
  ASSERT_TRUE(rec.contains("partial")) << rec.dump();
  EXPECT_TRUE(rec["partial"].contains("metrics"));
  EXPECT_TRUE(rec["partial"].contains("timing"));
  EXPECT_TRUE(rec["partial"].contains("classes"));
  EXPECT_TRUE(rec["partial"].contains("gpu_bytes"));
  // Nor a warning about its figures (the reference's noise against its RMSE).
  EXPECT_FALSE(rec.contains("warnings")) << rec.dump();
  const json& check = rec["visibility_check"];
  EXPECT_EQ(check["nonfinite"], 48 + 24);
  EXPECT_EQ(check["below_0"], 20);
  EXPECT_EQ(check["above_1"], 21);

  // invalid.png marks exactly the offending pixels, by kind.
  ASSERT_EQ(rec["images"]["invalid"], job_dir + "/invalid.png");
  const core::ImageF mask =
      metrics::io::read_image((run_dir / rec["images"]["invalid"].get<std::string>()).string());
  ASSERT_EQ(mask.width, kW);
  ASSERT_EQ(mask.height, kH);
  ASSERT_EQ(mask.channels, 3);
  const std::vector<int> want = expected_kinds();
  std::int64_t counts[4] = {0, 0, 0, 0};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float r = mask.at(x, y, 0), g = mask.at(x, y, 1), b = mask.at(x, y, 2);
      const int kind = r == 1 && g == 0 && b == 0   ? 1
                       : r == 0 && g == 0 && b == 1 ? 2
                       : r == 1 && g == 1 && b == 0 ? 3
                       : r == 0 && g == 0 && b == 0 ? 0
                                                    : -1;
      ++counts[std::max(kind, 0)];
      EXPECT_EQ(kind, want[size_t(y) * kW + x]) << "pixel " << x << ", " << y;
    }
  EXPECT_EQ(counts[1], check["nonfinite"].get<std::int64_t>());
  EXPECT_EQ(counts[2], check["below_0"].get<std::int64_t>());
  EXPECT_EQ(counts[3], check["above_1"].get<std::int64_t>());

  // The job that passed wrote no invalid.png.
  EXPECT_FALSE(ok["images"].contains("invalid"));
}

}  // namespace
}  // namespace sb::test
