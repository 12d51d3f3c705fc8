// The timing control is a baseline, never a competitor (issue 61): with
// `none` as every job's control, fastest of all, it is on no Pareto front
// (the pgfplots CSV's `pareto`, the error_time chart's labelled front),
// whether its error is the largest or the smallest; it is still drawn,
// marked as the control. The fronts expected here are worked out by hand
// from control_run.h's numbers (time ascending: shadow_map 11.8, pcf_box
// 12.3, pcss 14.1, shadow_volume 14.7, vsm 27.7; RMSE 0.0932, 0.0723,
// 0.0208, 0.0927, 0.0270): each of the first three is more accurate than
// everything faster, shadow_volume and vsm are beaten by pcss.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../metrics/test_util.h"
#include "control_run.h"
#include "results/charts.h"
#include "results/pgf_csv.h"

namespace sb {

namespace {

const std::vector<std::string> kFront = {"shadow_map/size=1024", "pcf_box/k=3,size=1024",
                                         "pcss/size=1024"};

// The CSV's rows as (technique cell, pareto, control).
std::vector<std::vector<std::string>> csv_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "technique,time_ms,time_p10_ms,time_p90_ms,error,pareto,control");
  while (std::getline(in, line)) {
    // The technique is in braces and may hold commas; the rest are numbers.
    const size_t close = line.find("},");
    std::vector<std::string> cells = {line.substr(1, close - 1)};
    std::istringstream rest(line.substr(close + 2));
    for (std::string cell; std::getline(rest, cell, ',');) cells.push_back(cell);
    cells.resize(7);  // a CSV without the control column reads "" there
    rows.push_back({cells[0], cells[5], cells[6]});
  }
  return rows;
}

class ControlBaseline : public ::testing::TestWithParam<double> {};

TEST_P(ControlBaseline, TheControlIsNotOnThePgfplotsFront) {
  const auto records = test::control_run_records(GetParam());
  const auto rows = csv_rows(
      results::make_error_time_csv(test::record_pointers(records), "visibility.geometry.rmse"));
  ASSERT_EQ(rows.size(), 6U);
  std::vector<std::string> front;
  for (const auto& row : rows) {
    if (row[1] == "1") front.push_back(row[0]);
    EXPECT_EQ(row[2], row[0] == "none" ? "1" : "0") << row[0];
  }
  EXPECT_EQ(rows[0][0], "none");  // drawn: the fastest row
  EXPECT_EQ(front, (std::vector<std::string>{"shadow\\_map/size=1024", "pcf\\_box/k=3,size=1024",
                                             "pcss/size=1024"}));
}

TEST_P(ControlBaseline, TheControlIsNotOnTheChartsFrontButDrawnAsTheControl) {
  if (const std::string why = results::charts_unavailable_reason(); !why.empty())
    GTEST_SKIP() << "charts cannot be drawn here: " << why;
  test::TempDir dir("control_chart");
  const auto charts =
      results::write_charts(test::control_run_records(GetParam()), dir.path().string());
  const auto it = std::find_if(charts.begin(), charts.end(),
                               [](const results::ChartFile& c) { return c.kind == "error_time"; });
  ASSERT_NE(it, charts.end());
  EXPECT_EQ(it->pareto, kFront);
  EXPECT_NE(std::find(it->series.begin(), it->series.end(), "none"), it->series.end());
  std::ifstream in(std::filesystem::path(it->svg).replace_extension(".json"));
  const auto data = nlohmann::json::parse(in);
  for (const auto& p : data["points"]) EXPECT_EQ(p["control"], p["label"] == "none") << p;
  std::ifstream svg(it->svg);
  const std::string text{std::istreambuf_iterator<char>(svg), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("none (control)"), std::string::npos);  // its legend entry
}

// 0.30: the control is the least accurate; 0.001: the most accurate too,
// and would then be the whole front.
INSTANTIATE_TEST_SUITE_P(ControlError, ControlBaseline, ::testing::Values(0.30, 0.001));

}  // namespace
}  // namespace sb
