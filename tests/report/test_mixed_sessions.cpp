// Records timed by more than one `run` session (record["session"], a resumed
// run folder) are never shown side by side without saying so: summary.md,
// the HTML report and the LaTeX export carry a banner naming the sessions
// and a "session" column of their letters; records of one session carry
// neither. The end-to-end path (a real resumed run) is
// tests/e2e/test_sessions.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "../record/sample_records.h"
#include "results/banner.h"
#include "results/html_report.h"
#include "results/latex_export.h"
#include "results/report.h"
#include "results/sessions.h"

namespace sb::test {

using record::JobRecord;
using record::JobStatus;
using record::SessionRecord;
using results::make_markdown;
using results::report_banners;
using results::Sessions;

namespace {

namespace fs = std::filesystem;

SessionRecord session(const std::string& id, const std::string& started, double load) {
  SessionRecord s;
  s.id = id;
  s.started = started;
  s.host = "vm";
  s.load_average = load;
  return s;
}

JobRecord timed(const std::string& technique, std::optional<SessionRecord> s,
                JobStatus status = JobStatus::Ok) {
  JobRecord r = identity_record("sphere_grid", "64x48", technique, status);
  if (status == JobStatus::Ok) r.timing = coarse_timing({2.0, 2.1, 2.2}, {1.0, 1.1, 1.2});
  r.session = std::move(s);
  return r;
}

const SessionRecord kFirst = session("00000000000000aa", "2026-12-07T10:00:00Z", 0.25);
const SessionRecord kSecond = session("00000000000000bb", "2026-12-07T11:00:00Z", 3.5);

// Three ok jobs of two sessions, the first session's first, and a failed job
// of a third (a failed job has no times to mix).
std::vector<JobRecord> resumed_run() {
  return {
      timed("none", kFirst), timed("pcf", kSecond), timed("vsm", kFirst),
      timed("esm", session("00000000000000cc", "2026-12-07T12:00:00Z", 1.0), JobStatus::Failed)};
}

std::string file_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(MixedSessions, TheOkRecordsSessionsAreLetteredInOrderOfFirstAppearance) {
  const std::vector<JobRecord> records = resumed_run();
  const Sessions sessions(records);
  EXPECT_EQ(sessions.count(), 2u);
  EXPECT_TRUE(sessions.mixed());
  EXPECT_EQ(sessions.letter(records[0]), "A");
  EXPECT_EQ(sessions.letter(records[1]), "B");
  EXPECT_EQ(sessions.letter(records[2]), "A");
  EXPECT_EQ(sessions.letter(records[3]), "");  // failed: no times
}

TEST(MixedSessions, RecordsWithoutASessionAreOneSessionOfTheirOwn) {
  const std::vector<JobRecord> old_only = {timed("none", std::nullopt), timed("pcf", std::nullopt)};
  EXPECT_FALSE(Sessions(old_only).mixed());
  EXPECT_TRUE(report_banners(old_only).empty());
  const std::vector<JobRecord> old_and_new = {timed("none", std::nullopt), timed("pcf", kFirst)};
  const auto banner = Sessions(old_and_new).banner();
  ASSERT_TRUE(banner);
  ASSERT_EQ(banner->items.size(), 2u);
  EXPECT_NE(banner->items[0].find("no session recorded"), std::string::npos) << banner->items[0];
}

TEST(MixedSessions, TheBannerCountsTheJobsAndNamesEachSession) {
  const auto banner = Sessions(resumed_run()).banner();
  ASSERT_TRUE(banner);
  EXPECT_EQ(banner->title, "Mixed sessions");
  EXPECT_NE(banner->text.find("these 3 jobs were measured in 2 sessions"), std::string::npos)
      << banner->text;
  EXPECT_NE(banner->text.find("times from different sessions are not comparable"),
            std::string::npos);
  ASSERT_EQ(banner->items.size(), 2u);
  EXPECT_EQ(banner->items[0],
            "A: session 00000000000000aa, started 2026-12-07T10:00:00Z on vm, load average 0.25: "
            "2 jobs");
  EXPECT_EQ(banner->items[1],
            "B: session 00000000000000bb, started 2026-12-07T11:00:00Z on vm, load average 3.50: "
            "1 job");
}

TEST(MixedSessions, OneSessionHasNoBannerAndNoColumn) {
  const std::vector<JobRecord> records = {timed("none", kFirst), timed("pcf", kFirst),
                                          timed("vsm", kSecond, JobStatus::Failed)};
  EXPECT_FALSE(Sessions(records).mixed());
  EXPECT_TRUE(report_banners(records).empty());
  const std::string md = make_markdown(records, "one session");
  EXPECT_EQ(md.find("Mixed sessions"), std::string::npos) << md;
  EXPECT_EQ(md.find("| session |"), std::string::npos) << md;
}

TEST(MixedSessions, SummaryMarkdownHasTheBannerAndASessionColumn) {
  const std::string md = make_markdown(resumed_run(), "resumed");
  EXPECT_NE(md.find("**Mixed sessions:** these 3 jobs were measured in 2 sessions"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| technique | session | status |"), std::string::npos) << md;
  EXPECT_NE(md.find("| none | A | ok |"), std::string::npos) << md;
  EXPECT_NE(md.find("| pcf | B | ok |"), std::string::npos) << md;
  EXPECT_NE(md.find("| vsm | A | ok |"), std::string::npos) << md;
  EXPECT_NE(md.find("| esm |  | failed |"), std::string::npos) << md;
}

TEST(MixedSessions, TheHtmlReportHasTheBannerAndASessionColumn) {
  const fs::path dir = test_folder("sb_mixed_sessions_");
  results::write_html_report(resumed_run(), dir.string(), (dir / "report").string(), {}, "resumed",
                             false);
  const std::string page = file_text(dir / "report" / "index.html");
  EXPECT_NE(page.find("<strong>Mixed sessions:</strong> these 3 jobs were measured in 2 sessions"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"mono\">run --retime</span>"), std::string::npos);
  EXPECT_EQ(count(page, "<th>session</th>"), 1u);  // one (scene, resolution) table
  EXPECT_NE(page.find("<td class=\"name\">pcf</td><td class=\"num\">B</td>"), std::string::npos);
}

TEST(MixedSessions, TheLatexExportHasTheBannerAndASessionColumn) {
  const fs::path dir = test_folder("sb_mixed_sessions_latex_");
  results::LatexOptions options;
  options.title = "resumed";
  const results::LatexFiles files =
      results::write_latex(resumed_run(), (dir / "latex").string(), options);
  const std::string doc = file_text(files.document);
  EXPECT_NE(doc.find("\\paragraph{Mixed sessions:} these 3 jobs were measured in 2 sessions"),
            std::string::npos)
      << doc;
  EXPECT_NE(doc.find("\\item[--] B: session 00000000000000bb"), std::string::npos) << doc;
  ASSERT_EQ(files.tables.size(), 1u);
  const std::string table = file_text(files.tables[0]);
  EXPECT_NE(table.find("Technique & Session & "), std::string::npos) << table;
  EXPECT_NE(table.find("pcf & B & "), std::string::npos) << table;
}

}  // namespace sb::test
