// Sessions through the driver (record["session"], docs/performance.md
// "Sessions and --retime"): a run folder resumed after one job's settings
// changed holds records of two `run` sessions, and summary.md, the HTML
// report and the LaTeX export say so in a banner and a session column;
// `run --retime` then times every kept job again in one session, keeping
// their errors, images and reference byte for byte and making no reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "../common/cli_run.h"
#include "e2e_util.h"

namespace sb::test {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const char* const kNone = "sphere_grid--grid=2__32x24__none";
const char* const kVsm = "sphere_grid--grid=2__32x24__vsm--size=64";

// Two jobs, each as cheap as a job gets; the reference is not cached, so
// that each reference made is computed and logged.
json two_job_config() {
  return {{"name", "sessions"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
          {"techniques", {"none", {{"name", "vsm"}, {"params", {{"size", 64}}}}}},
          {"resolutions", {{32, 24}}},
          {"frames", {{"warmup", 0}, {"timed", 3}}},
          {"reference", {{"spp", 16}, {"cache", false}}}};
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliRun run_into(const fs::path& out, const std::string& options = "") {
  const fs::path config = out.string() + ".json";
  std::ofstream(config) << two_job_config().dump();
  return run_command(std::string(SHADOWBENCH_EXE) + " run '" + config.string() + "' --out '" +
                     out.string() + "' " + options);
}

CliRun report(const fs::path& out) {
  return run_command(std::string(SHADOWBENCH_EXE) + " report '" + out.string() +
                     "' --latex --no-viewer-data");
}

// The run folder's records by job id.
std::map<std::string, json> records_of(const fs::path& out) {
  std::map<std::string, json> by_id;
  for (json& r : jsonl_records(out)) {
    const std::string id = r["job_id"].get<std::string>();  // before r is moved from
    by_id[id] = std::move(r);
  }
  return by_id;
}

std::string session_of(const json& record) { return record["session"]["id"].get<std::string>(); }

// Makes the stored record of `job` that of other settings: a rerun runs it again.
void respecify(const fs::path& out, const std::string& job) {
  const fs::path file = out / "records" / (job + ".json");
  json r = json::parse(text_of(file));
  r["spec_hash"] = "0123456789abcdef";
  std::ofstream(file) << r.dump();
}

// A reference made (not kept from a record) is logged as "reference <scene> @ <WxH>: ...".
bool made_a_reference(const CliRun& r) {
  return r.output.find("reference sphere_grid") != std::string::npos;
}

// A folder of two sessions: both jobs in the first, then vsm's again in the second.
fs::path resumed_run(const std::string& name) {
  const fs::path out = fs::path(fresh_test_folder(name)) / "out";
  const CliRun first = run_into(out);
  EXPECT_EQ(first.exit_code, 0) << first.output;
  respecify(out, kVsm);
  const CliRun second = run_into(out);
  EXPECT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("1 ok, 0 skipped, 0 failed, 1 resumed"), std::string::npos)
      << second.output;
  return out;
}

}  // namespace

TEST(Sessions, OneRunIsOneSessionAndItsReportsHaveNoBanner) {
  const fs::path out = fs::path(fresh_test_folder("sb_sessions_one_")) / "out";
  const CliRun r = run_into(out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto records = records_of(out);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(session_of(records.at(kNone)), session_of(records.at(kVsm)));
  EXPECT_EQ(records.at(kNone)["session"].count("retimed_from"), 0u);
  ASSERT_EQ(report(out).exit_code, 0);
  for (const fs::path& file : {out / "summary.md", out / "report" / "index.html",
                               out / "report" / "latex" / "tables.tex"}) {
    const std::string text = text_of(file);
    EXPECT_EQ(text.find("Mixed sessions"), std::string::npos) << file;
    EXPECT_EQ(text.find("<th>session</th>"), std::string::npos) << file;
    EXPECT_EQ(text.find("| session |"), std::string::npos) << file;
  }
  EXPECT_EQ(
      text_of(out / "report" / "latex" / "table-sphere-grid-grid-2-32x24.tex").find("Session"),
      std::string::npos);
}

TEST(Sessions, AResumedRunsReportsBannerTheSessionsAndMarkEachRow) {
  const fs::path out = resumed_run("sb_sessions_mixed_");
  const auto records = records_of(out);
  const std::string first = session_of(records.at(kNone)), second = session_of(records.at(kVsm));
  EXPECT_NE(first, second);

  const std::string md = text_of(out / "summary.md");
  EXPECT_NE(md.find("**Mixed sessions:** these 2 jobs were measured in 2 sessions"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("times from different sessions are not comparable"), std::string::npos);
  EXPECT_NE(md.find("- A: session " + first), std::string::npos) << md;
  EXPECT_NE(md.find("- B: session " + second), std::string::npos) << md;
  EXPECT_NE(md.find("| none | A | ok |"), std::string::npos) << md;
  EXPECT_NE(md.find("| vsm/size=64 | B | ok |"), std::string::npos) << md;

  const CliRun r = report(out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string page = text_of(out / "report" / "index.html");
  EXPECT_NE(page.find("<strong>Mixed sessions:</strong> these 2 jobs were measured in 2 sessions"),
            std::string::npos);
  EXPECT_NE(page.find("<li>B: session " + second), std::string::npos);
  EXPECT_NE(page.find("<th>session</th>"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"name\">vsm/size=64</td><td class=\"num\">B</td>"),
            std::string::npos);
  const std::string tex = text_of(out / "report" / "latex" / "tables.tex");
  EXPECT_NE(tex.find("\\paragraph{Mixed sessions:} these 2 jobs were measured in 2 sessions"),
            std::string::npos)
      << tex;
  const std::string table =
      text_of(out / "report" / "latex" / "table-sphere-grid-grid-2-32x24.tex");
  EXPECT_NE(table.find("Technique & Session & "), std::string::npos) << table;
  // The row's first cells: the name (with a noisy job's mark, if any), then the session.
  std::istringstream rows(table);
  bool marked = false;
  for (std::string row; std::getline(rows, row);)
    if (row.starts_with("vsm/size=64")) marked = row.find(" & B & ") != std::string::npos;
  EXPECT_TRUE(marked) << table;
}

TEST(Sessions, RetimeMakesAResumedRunOneSessionKeepingItsErrorsAndImages) {
  const fs::path out = resumed_run("sb_sessions_retime_");
  const auto before = records_of(out);
  std::map<std::string, std::string> image_bytes;  // every image a record names
  for (const auto& [id, r] : before)
    for (const auto& [key, path] : r["images"].items())
      if (path.is_string())
        image_bytes[path.get<std::string>()] = text_of(out / path.get<std::string>());
  ASSERT_GE(image_bytes.size(), 4u);

  // Job isolation first (each job in a child of its own), then in-process.
  std::string previous;
  for (const std::string isolation : {"job", "none"}) {
    SCOPED_TRACE(isolation);
    const CliRun r = run_into(out, "--retime --isolation " + isolation);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("2 ok, 0 skipped, 0 failed, 0 resumed (2 of the ok re-timed"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(made_a_reference(r)) << r.output;
    const auto after = records_of(out);
    ASSERT_EQ(after.size(), 2u);
    const std::string now = session_of(after.at(kNone));
    EXPECT_EQ(session_of(after.at(kVsm)), now);
    EXPECT_NE(now, previous);
    for (const auto& [id, r0] : before) {
      SCOPED_TRACE(id);
      const json& r1 = after.at(id);
      EXPECT_NE(session_of(r1), session_of(r0));
      EXPECT_EQ(r1["session"]["retimed_from"],
                previous.empty() ? r0["session"]["id"] : json(previous));
      // Byte-equal errors, reference and images; new times.
      EXPECT_EQ(r1["metrics"].dump(), r0["metrics"].dump());
      EXPECT_EQ(r1["classes"].dump(), r0["classes"].dump());
      EXPECT_EQ(r1["reference"].dump(), r0["reference"].dump());
      EXPECT_EQ(r1["images"].dump(), r0["images"].dump());
      EXPECT_NE(r1["timing"]["frame"].dump(), r0["timing"]["frame"].dump());
    }
    for (const auto& [path, bytes] : image_bytes)
      EXPECT_TRUE(text_of(out / path) == bytes) << path << " was written again";
    const std::string md = text_of(out / "summary.md");
    EXPECT_EQ(md.find("Mixed sessions"), std::string::npos) << md;
    EXPECT_EQ(md.find("| session |"), std::string::npos) << md;
    previous = now;
  }
}

TEST(Sessions, RetimeRunsAChangedJobWholeBesideTheRetimedOnes) {
  const fs::path out = fs::path(fresh_test_folder("sb_sessions_retime_changed_")) / "out";
  ASSERT_EQ(run_into(out).exit_code, 0);
  const auto before = records_of(out);
  respecify(out, kVsm);
  const CliRun r = run_into(out, "--retime");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(made_a_reference(r)) << r.output;  // for vsm, which runs whole
  EXPECT_NE(r.output.find("(1 of the ok re-timed"), std::string::npos) << r.output;
  const auto after = records_of(out);
  EXPECT_EQ(session_of(after.at(kNone)), session_of(after.at(kVsm)));
  EXPECT_EQ(after.at(kNone)["session"]["retimed_from"], before.at(kNone)["session"]["id"]);
  EXPECT_EQ(after.at(kVsm)["session"].count("retimed_from"), 0u);
  EXPECT_EQ(after.at(kNone)["metrics"].dump(), before.at(kNone)["metrics"].dump());
}

}  // namespace sb::test
