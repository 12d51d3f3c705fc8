// Debugging a broken plugin in minutes (issue 62): `run --only` runs exactly
// the jobs it selects and keeps the run folder's other records; a crash's
// reason names the phase and a command that reproduces the job in-process;
// a GLSL error names the plugin's own line and the assembled source is
// written; a failed visibility check leaves its mask even without images;
// a reason of several lines is one row of summary.md.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "broken_plugin_glsl.h"
#include "metrics/image_io.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kW = 40, kH = 30;

CliRun shadowbench(const std::string& args) {
  return run_command("SHADOWBENCH_PLUGIN_PATH='" DEBUGGING_PLUGIN_DIR
                     ":" INVALID_VISIBILITY_PLUGIN_DIR "' '" SHADOWBENCH_EXE "' " +
                     args);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A small, quick experiment: a 2×2 sphere grid, no control job.
std::string write_config(const fs::path& dir, const json& techniques,
                         const json& resolutions = json::array({{kW, kH}})) {
  const json config = {{"name", "debugging"},
                       {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                       {"techniques", techniques},
                       {"resolutions", resolutions},
                       {"frames", {{"warmup", 0}, {"timed", 2}, {"control", nullptr}}},
                       {"reference", {{"spp", 4}}}};
  const fs::path file = dir / "config.json";
  std::ofstream(file) << config.dump(2);
  return file.string();
}

const json* find(const std::vector<json>& records, const std::string& technique_variant) {
  for (const auto& r : records)
    if (r["technique_variant"] == technique_variant) return &r;
  return nullptr;
}

std::string reason(const json& record) { return record.value("reason", std::string()); }

// The broken plugin's one job, in `mode`, run into a new folder: it fails.
struct BrokenRun {
  std::string out;  // the run folder
  json record;      // its one record
};

BrokenRun run_broken(const std::string& mode) {
  const fs::path dir = test_folder("sb_debugging_");
  const std::string config =
      write_config(dir, json::array({{{"name", "broken"}, {"params", {{"mode", mode}}}}}));
  const std::string out = (dir / "run").string();
  const CliRun r = shadowbench("run " + config + " --out " + out + " --no-cache --no-images");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  if (records.size() != 1u) {
    ADD_FAILURE() << records.size() << " records, not 1:\n" << r.output;
    return {out, json::object()};
  }
  return {out, records[0]};
}

// (resolution, technique variant) of each record.
std::set<std::pair<std::string, std::string>> jobs_of(const std::vector<json>& records) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& r : records) out.emplace(r["resolution"], r["technique_variant"]);
  return out;
}

TEST(Debugging, OnlyRunsExactlyTheSelectedJobsAndKeepsTheOthersRecords) {
  const fs::path dir = test_folder("sb_debugging_");
  const std::string config = write_config(dir, json::array({"none", "shadow_map", "pcf_box"}),
                                          json::array({{kW, kH}, {48, 36}}));
  const std::string out = (dir / "run").string();
  const std::string common = " --out " + out + " --no-cache --no-images --quiet";

  // plan --only lists what run --only would run: the union of its patterns.
  const CliRun plan = shadowbench("plan " + config + " --only '*__40x30__*' --only '*pcf_box*'");
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("selects 4 of 6 jobs"), std::string::npos) << plan.output;

  const CliRun first =
      shadowbench("run " + config + common + " --only '*__40x30__*' --only '*pcf_box*'");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("4 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos)
      << first.output;
  const std::set<std::pair<std::string, std::string>> want_first = {
      {"40x30", "none"}, {"40x30", "shadow_map"}, {"40x30", "pcf_box"}, {"48x36", "pcf_box"}};
  const auto after_first = jsonl_records(out);
  EXPECT_EQ(jobs_of(after_first), want_first);
  size_t files = 0;
  for (const auto& f : fs::directory_iterator(fs::path(out) / "records"))
    files += f.path().extension() == ".json" ? 1 : 0;
  EXPECT_EQ(files, 4u);

  // A second selection runs its job alone; the first four stay as they were.
  const CliRun second = shadowbench("run " + config + common + " --only '*__48x36__none'");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("1 ok, 0 skipped, 0 failed, 0 resumed"), std::string::npos)
      << second.output;
  const auto after_second = jsonl_records(out);
  auto want_second = want_first;
  want_second.emplace("48x36", "none");
  EXPECT_EQ(jobs_of(after_second), want_second);
  for (const auto& kept : after_first) {
    bool same = false;
    for (const auto& r : after_second)
      same = same || (r["job_id"] == kept["job_id"] && r["finished_at"] == kept["finished_at"] &&
                      r["session"] == kept["session"]);
    EXPECT_TRUE(same) << kept["job_id"] << " changed or went";
  }
  // The reports cover the folder: five rows of jobs (the rankings aside).
  const std::string summary = slurp(fs::path(out) / "summary.md");
  std::istringstream lines(summary);
  size_t rows = 0;
  for (std::string line; std::getline(lines, line);)
    for (const std::string t : {"| none |", "| shadow_map |", "| pcf_box |"})
      rows += line.rfind(t, 0) == 0 ? 1 : 0;
  EXPECT_EQ(rows, 5u) << summary;
}

TEST(Debugging, AnOnlyThatSelectsNothingIsBadInputNamingThePatternAndSomeIds) {
  const fs::path dir = test_folder("sb_debugging_");
  const std::string config = write_config(dir, json::array({"none", "shadow_map"}));
  for (const std::string& command : {"run --out " + (dir / "run").string(), std::string("plan")}) {
    std::string args = command;
    args += " " + config + " --only '*__40x30__*' --only '*__640x480__*'";
    const CliRun r = shadowbench(args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("'*__640x480__*' selects no job"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("__40x30__shadow_map"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "run" / "results.jsonl"));
}

TEST(Debugging, ACrashInPrepareNamesThePhaseAndACommandThatReproducesItInProcess) {
  const fs::path dir = test_folder("sb_debugging_");
  const std::string config = write_config(
      dir, json::array({"none", {{"name", "broken"}, {"params", {{"mode", "null"}}}}}));
  const std::string out = (dir / "run").string();
  const CliRun r = shadowbench("run " + config + " --out " + out + " --no-cache --no-images");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  const json* crashed = find(records, "broken/mode=null");
  ASSERT_NE(crashed, nullptr) << r.output;
  const std::string why = reason(*crashed);
  EXPECT_EQ(why.rfind("crashed in prepare(): its process killed by signal 11 (SIGSEGV", 0), 0u)
      << why;
  EXPECT_NE(r.output.find("crashed in prepare()"), std::string::npos) << r.output;

  // The command suggested: the same run, this job only, in this process.
  const std::string marker = "; reproduce in-process: gdb --args ";
  const size_t at = why.find(marker);
  ASSERT_NE(at, std::string::npos) << why;
  const std::string command = why.substr(at + marker.size());
  EXPECT_NE(
      command.find(" --only '" + (*crashed)["job_id"].get<std::string>() + "' --isolation none"),
      std::string::npos)
      << command;
  // Run without gdb, it crashes this process itself: the job, in-process.
  const CliRun again = run_command("SHADOWBENCH_PLUGIN_PATH='" DEBUGGING_PLUGIN_DIR "' " + command);
  EXPECT_EQ(again.exit_code, 128 + 11) << command << "\n" << again.output;
  // ... and it ran that job alone: the healthy job was resumed, not rerun.
  EXPECT_EQ(again.output.find("none: ok"), std::string::npos) << again.output;
}

TEST(Debugging, AGlslTypoNamesThePluginsOwnLineAndWritesTheAssembledSource) {
  const BrokenRun run = run_broken("typo");
  ASSERT_TRUE(run.record.contains("job_id"));
  const std::string& out = run.out;
  const std::string why = reason(run.record);
  // Mesa's "1:4(3): error": source string 1, the plugin's lit_fraction, line 4.
  EXPECT_TRUE(std::regex_search(
      why, std::regex("\\b1:" + std::to_string(broken::kTypoLine) + "\\(\\d+\\): error")))
      << why;
  EXPECT_NE(why.find("1 is lit_fraction as written"), std::string::npos) << why;
  const std::string rel =
      "jobs/" + run.record["job_id"].get<std::string>() + "/shader-broken_lookup-fragment.glsl";
  EXPECT_NE(why.find(rel), std::string::npos) << why;
  const std::string source = slurp(fs::path(out) / rel);
  EXPECT_NE(source.find(broken::kTypoGlsl), std::string::npos) << source;
  EXPECT_EQ(source.rfind("#version 450", 0), 0u) << source;
  // One row: no line break, escaped or not.
  EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  EXPECT_EQ(why.find("\\n"), std::string::npos) << why;
}

TEST(Debugging, AnUndefinedNameAfterKitGlslNamesThePluginsOwnLine) {
  const BrokenRun run = run_broken("undefined");
  ASSERT_TRUE(run.record.contains("job_id"));
  const std::string why = reason(run.record);
  // Mesa reports a semantic error with source string 0 and the piece's own
  // line: the reason still says source string 1, line 5.
  EXPECT_TRUE(std::regex_search(
      why, std::regex("\\b1:" + std::to_string(broken::kUndefinedLine) + "\\(\\d+\\): error")))
      << why;
  EXPECT_EQ(why.find("0:" + std::to_string(broken::kUndefinedLine) + "("), std::string::npos)
      << why;
}

TEST(Debugging, AReasonOfSeveralLinesIsOneRowOfSummaryMdAndWhollyInAFile) {
  const BrokenRun run = run_broken("lines");
  ASSERT_TRUE(run.record.contains("job_id"));
  const std::string& out = run.out;
  const std::string id = run.record["job_id"];
  EXPECT_EQ(reason(run.record),
            "broken: prepare: first line of the failure / second line | with a bar / third line, "
            "indented (the whole message: jobs/" +
                id + "/failure.txt)");
  EXPECT_EQ(slurp(fs::path(out) / "jobs" / id / "failure.txt"),
            std::string("broken: prepare: ") + broken::kLinesMessage);
  // summary.md: the job's row is one line, its cells those of the header.
  std::istringstream summary(slurp(fs::path(out) / "summary.md"));
  std::string header, row;
  for (std::string line; std::getline(summary, line);) {
    if (line.rfind("| technique", 0) == 0) header = line;
    if (line.rfind("| broken/mode=lines ", 0) == 0) row = line;
  }
  ASSERT_FALSE(row.empty()) << slurp(fs::path(out) / "summary.md");
  EXPECT_NE(row.find("first line of the failure / second line \\| with a bar / third line"),
            std::string::npos)
      << row;
  const auto bars = [](const std::string& s) {
    size_t n = 0;
    for (size_t i = 0; i < s.size(); ++i) n += s[i] == '|' && (i == 0 || s[i - 1] != '\\');
    return n;
  };
  EXPECT_EQ(bars(row), bars(header)) << header << "\n" << row;
}

TEST(Debugging, ANanWritingJobsFolderHoldsTheMaskOfItsBadPixelsEvenWithoutImages) {
  const fs::path dir = test_folder("sb_debugging_");
  const std::string config = write_config(dir, json::array({"writes_invalid"}));
  const std::string out = (dir / "run").string();
  const CliRun r = shadowbench("run " + config + " --out " + out + " --no-cache --no-images");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 1u) << r.output;
  const json& rec = records[0];
  EXPECT_NE(reason(rec).find("NaN/Inf"), std::string::npos) << reason(rec);
  const std::string rel = "jobs/" + rec["job_id"].get<std::string>() + "/invalid.png";
  ASSERT_EQ(rec["images"].value("invalid", ""), rel) << rec.dump(1);
  const core::ImageF mask = metrics::io::read_image((fs::path(out) / rel).string());
  ASSERT_EQ(mask.width, kW);
  ASSERT_EQ(mask.height, kH);
  ASSERT_EQ(mask.channels, 3);
  // The plugin writes NaN in 8×6 pixels and +inf in 4×6 at the bottom left
  // (GL's y up: the image's last rows): red, as the record counts them.
  std::int64_t red = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool is_red = mask.at(x, y, 0) == 1 && mask.at(x, y, 1) == 0 && mask.at(x, y, 2) == 0;
      red += is_red;
      if (x < 12 && y >= kH - 6) {
        EXPECT_TRUE(is_red) << "pixel " << x << ", " << y;
      }
    }
  EXPECT_EQ(red, 48 + 24);
  EXPECT_EQ(rec["visibility_check"]["nonfinite"], red);
  // Only the mask: --no-images keeps the job's other images out.
  EXPECT_FALSE(
      fs::exists(fs::path(out) / "jobs" / rec["job_id"].get<std::string>() / "visibility.exr"));
}

}  // namespace
}  // namespace sb::test
