// The console's per-job line prints the error the tables print under `rmse`.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "results/report.h"
#include "run/job_line.h"

namespace sb {

using record::JobRecord;
using record::JobStatus;
using record::MetricsRecord;
using record::RegionStats;
using record::TimingRecord;
using results::make_csv;
using run::job_line;

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, sep)) out.push_back(cell);
  return out;
}

// The results.csv cell of `column` in the only row of a one-record table.
std::string csv_cell(const JobRecord& r, const std::string& column) {
  const std::vector<std::string> lines = split(make_csv({r}), '\n');
  EXPECT_GE(lines.size(), 2u);
  const std::vector<std::string> header = split(lines.at(0), ',');
  const std::vector<std::string> row = split(lines.at(1), ',');
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == column) return row.at(i);
  ADD_FAILURE() << "no column " << column << " in " << lines.at(0);
  return "";
}

// A finished job whose `all` and `geometry` RMSEs differ, as they did on a
// 2x2 sphere grid at 96x72 (0.03718 over all, 0.03727 over geometry).
JobRecord finished_job() {
  JobRecord r;
  r.scene_variant = "sphere_grid";
  r.resolution = "96x72";
  r.technique_variant = "pcss";
  r.status = JobStatus::Ok;
  TimingRecord t;
  t.frame.median = 1.5;
  t.technique.median = 0.5;
  r.timing = t;
  MetricsRecord m;
  m.visibility.all.rmse = 0.03718;
  RegionStats geometry;
  geometry.rmse = 0.03727;
  m.visibility.geometry = geometry;
  r.metrics = m;
  return r;
}

TEST(JobLine, PrintsTheRmseTheTableShows) {
  const JobRecord r = finished_job();
  const std::string line = job_line(r, 3, 20);
  const std::string table_rmse = csv_cell(r, "rmse");
  EXPECT_EQ(table_rmse, "0.03727");
  EXPECT_NE(line.find("geometry RMSE " + table_rmse), std::string::npos) << line;
  EXPECT_EQ(line.find("0.03718"), std::string::npos) << line;
  EXPECT_EQ(line.rfind("[3/20] sphere_grid @ 96x72  pcss: ok", 0), 0u) << line;
}

TEST(JobLine, AFailedJobShowsItsReason) {
  JobRecord r = finished_job();
  r.status = JobStatus::Failed;
  r.reason = "visibility outside [0,1]";
  EXPECT_EQ(job_line(r, 1, 2),
            "[1/2] sphere_grid @ 96x72  pcss: failed (visibility outside [0,1])");
}

}  // namespace
}  // namespace sb
