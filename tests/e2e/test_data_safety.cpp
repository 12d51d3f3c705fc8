// Results are never silently lost, mixed or stale, whatever the folder or the
// labels: reruns redo jobs whose settings changed, a busy run folder is
// refused, labels that used to share a file keep their own records, crafted
// records cannot make `report` write outside its folder, and bytes that are
// not UTF-8 do not cost the run its records.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../config/cli_runner.h"
#include "e2e_util.h"
#include "store/results_store.h"
#include "store/run_lock.h"

namespace sb::test {

using store::read_run_records;
using store::RunFolderLock;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Folder {
  fs::path dir = fresh_test_folder("shadowbench_test_safety_");
  std::string config(const std::string& name, const json& techniques, int spp = 4) const {
    const json c = {{"name", "safety"},
                    {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                    {"techniques", techniques},
                    {"resolutions", {{24, 16}}},
                    {"frames", {{"warmup", 0}, {"timed", 1}}},
                    {"reference", {{"spp", spp}, {"cache", false}}}};
    const fs::path p = dir / name;
    std::ofstream(p) << c.dump();
    return p.string();
  }
  std::string run(const std::string& config, const std::string& out,
                  const std::string& extra = "") const {
    return "run " + config + " --quiet --no-images --out '" + (dir / out).string() + "'" + extra;
  }
};

TEST(DataSafety, ARerunRedoesTheJobsWhoseSettingsChanged) {
  Folder f;
  const json techniques = {"none", {{"name", "shadow_map"}, {"params", {{"size", 64}}}}};
  auto r = run_cli(f.run(f.config("a.json", techniques, 4), "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli(f.run(f.config("a.json", techniques, 4), "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 0 skipped, 0 failed, 2 resumed"), std::string::npos) << r.output;
  // Same job ids, other reference: nothing may be "resumed" from the old run.
  r = run_cli(f.run(f.config("a.json", techniques, 8), "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 ok, 0 skipped, 0 failed, 0 resumed (2 earlier records had other "
                          "settings and were rerun)"),
            std::string::npos)
      << r.output;
  const auto records = read_run_records((f.dir / "out").string());
  ASSERT_EQ(records.size(), 2u);
  for (const json& rec : records) EXPECT_EQ(rec["reference"]["spp"], 8);
}

TEST(DataSafety, ABusyRunFolderIsRefusedNamingItsHolder) {
  Folder f;
  const std::string config = f.config("a.json", {"none"});
  {
    RunFolderLock held((f.dir / "out").string());
    const auto r = run_cli(f.run(config, "out"));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(
        r.output.find("is in use by another shadowbench run (pid " + std::to_string(::getpid())),
        std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(f.dir / "out" / "results.jsonl"));
  }
  const auto r = run_cli(f.run(config, "out"));  // released with its holder
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(DataSafety, LabelsThatUsedToShareAFileKeepTheirOwnRecords) {
  Folder f;
  const json techniques = {{{"name", "none"}, {"label", "α"}},
                           {{"name", "none"}, {"label", "β"}},
                           {{"name", "none"}, {"label", "x y"}},
                           {{"name", "none"}, {"label", "x-y"}},
                           {{"name", "none"}, {"label", "../../up"}}};
  const auto r = run_cli(f.run(f.config("a.json", techniques), "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("5 ok"), std::string::npos) << r.output;
  EXPECT_EQ(read_run_records((f.dir / "out").string()).size(), 5u);
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(f.dir / "out" / "records")) {
    EXPECT_NE(e.path().filename().string()[0], '.');
    ++files;
  }
  EXPECT_EQ(files, 5u);
  EXPECT_FALSE(fs::exists(f.dir / "up")) << "a label left the run folder";
}

TEST(DataSafety, CraftedRecordsCannotMakeReportWriteOutsideItsFolder) {
  Folder f;
  auto r = run_cli(f.run(f.config("a.json", {"none"}), "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path jsonl = f.dir / "out" / "results.jsonl";
  std::vector<json> records = read_run_records((f.dir / "out").string());
  ASSERT_EQ(records.size(), 1u);
  json crafted = records[0];
  crafted["resolution"] = "../../../escaped";
  crafted["scene_variant"] = "../../escaped_scene";
  crafted["scene"]["type"] = "../../escaped_type";
  crafted["job_id"] = "../../escaped_job";
  std::ofstream(jsonl, std::ios::app) << crafted.dump() << "\n";
  r = run_cli("report '" + (f.dir / "out").string() + "' --out '" +
              (f.dir / "out" / "rep").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const auto& e : fs::recursive_directory_iterator(f.dir)) {
    const std::string p = e.path().string();
    if (p.find("escaped") != std::string::npos) {
      EXPECT_EQ(p.rfind((f.dir / "out" / "rep").string(), 0), 0u) << p << " is outside the report";
    }
  }
  // A field of the wrong type is bad input, not an internal error.
  crafted["resolution"] = 42;
  std::ofstream(jsonl, std::ios::app) << crafted.dump() << "\n";
  r = run_cli("report '" + (f.dir / "out").string() + "' --out '" + (f.dir / "rep2").string() +
              "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(DataSafety, BytesThatAreNotUtf8CostNoRecord) {
  Folder f;
  const std::string config = f.config("a\xff.json", {"none"});
  const auto r = run_cli(f.run(config, "out\xfe"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto records = read_run_records((f.dir / "out\xfe").string());
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0]["status"], "ok");
  EXPECT_NE(records[0]["config"].get<std::string>().find("\xEF\xBF\xBD"), std::string::npos)
      << "the byte is written as U+FFFD";
}

}  // namespace
}  // namespace sb::test
