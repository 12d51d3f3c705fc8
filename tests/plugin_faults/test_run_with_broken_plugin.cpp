// `run` with a broken plugin in the path: the jobs naming a technique it may
// have registered fail with its reason, the others run (exit 1, as for any
// failed job). And a technique's throw names the phase it came from.
#include <gtest/gtest.h>

#include <string>

#include "broken_plugins.h"

namespace sb::test {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const nlohmann::json* record_of(const std::vector<nlohmann::json>& records,
                                const std::string& variant) {
  for (const auto& r : records)
    if (r["technique"]["variant"] == variant) return &r;
  return nullptr;
}

TEST(RunWithBrokenPlugin, FailsTheJobsOfItsTechniqueWithTheReasonAndRunsTheRest) {
  const auto dir = broken_plugin_folder();
  const std::string config = small_config(dir, R"(["none", "my_pcf", "shadow_map"])");
  const auto out = dir / "run";
  const CliRun r =
      shadowbench(dir.string(), "run " + config + " --out " + out.string() + " --no-cache");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const std::string why =
      "unknown technique \"my_pcf\" (plugin " + (dir / "my_pcf.so").string() + " failed to load: ";
  EXPECT_TRUE(has(r.output, "my_pcf: failed (" + why)) << "the console line\n" << r.output;
  EXPECT_TRUE(has(r.output, "2 ok, 0 skipped, 1 failed")) << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 3u) << r.output;
  const nlohmann::json* failed = record_of(records, "my_pcf");
  ASSERT_NE(failed, nullptr);
  EXPECT_EQ((*failed)["status"], "failed");
  const std::string reason = (*failed)["reason"];
  EXPECT_TRUE(has(reason, why)) << reason;
  EXPECT_TRUE(has(reason, "undefined symbol")) << reason;
  for (const char* ran : {"none", "shadow_map"}) {
    const nlohmann::json* rec = record_of(records, ran);
    ASSERT_NE(rec, nullptr) << ran;
    EXPECT_EQ((*rec)["status"], "ok") << rec->dump();
  }
}

TEST(RunWithBrokenPlugin, ATechniquesThrowNamesItsPhase) {
  const auto dir = test_folder("sb_phase_");
  const std::string config = small_config(
      dir, R"([{"name": "fault", "params": {"mode": "throw", "at": ["prepare", "frame"]}}])");
  const auto out = dir / "run";
  const CliRun r =
      shadowbench(FAULT_PLUGIN_DIR, "run " + config + " --out " + out.string() + " --no-cache");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 2u) << r.output;
  const std::string thrown = "fault plugin: thrown on demand";
  const nlohmann::json* prepare = record_of(records, "fault/mode=throw,at=prepare");
  const nlohmann::json* frame = record_of(records, "fault/mode=throw,at=frame");
  ASSERT_TRUE(prepare != nullptr && frame != nullptr) << r.output;
  EXPECT_EQ((*prepare)["reason"], "fault: prepare: " + thrown);
  EXPECT_EQ((*frame)["reason"], "fault: render: " + thrown);
  // The console line says the same.
  EXPECT_TRUE(has(r.output, "fault/mode=throw,at=prepare: failed (fault: prepare: " + thrown + ")"))
      << r.output;
}

}  // namespace
}  // namespace sb::test
