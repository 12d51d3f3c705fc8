// The reference's Embree ISA through the driver, as a user sets it: the
// record names the ISA that traced, a CPU without the ISA asked for is an
// environment error (exit 3) before any job, a malformed choice bad input
// (exit 2). The first config is the one that aborted on AVX2-only CPUs
// (4 spp: 12 of 16 packet lanes unused).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../config/cli_runner.h"
#include "e2e_util.h"
#include "reference/embree_isa.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;

struct IsaFolder {
  fs::path dir = fresh_test_folder("shadowbench_test_isa_cli_");
  std::string config(const std::string& spp, const std::string& extra = "") const {
    const fs::path p = dir / ("avx_" + spp + ".json");
    std::ofstream(p) << R"({"name":"avx","scenes":[{"type":"sphere_grid","params":{"grid":2}}],)"
                     << R"("techniques":["none"],"resolutions":[[32,24]],)"
                     << R"("frames":{"warmup":1,"timed":1},"reference":{"spp":)" << spp
                     << R"(,"seed":1,"cache":false)" << extra << "}}";
    return p.string();
  }
  nlohmann::json record(const std::string& out) const {
    std::ifstream in(dir / out / "results.jsonl");
    std::string line;
    std::getline(in, line);
    return nlohmann::json::parse(line);
  }
};

TEST(ReferenceIsaCli, TheIssuesConfigRunsAndRecordsTheIsa) {
  IsaFolder f;
  for (const char* spp : {"1", "4", "15", "17"}) {
    const std::string out = std::string("out_") + spp;
    const auto r = run_cli("run " + f.config(spp) + " --quiet --out " + (f.dir / out).string());
    ASSERT_EQ(r.exit_code, 0) << "spp " << spp << ": " << r.output;
    const nlohmann::json rec = f.record(out);
    EXPECT_EQ(rec["status"], "ok");
    EXPECT_EQ(rec["reference"]["embree_isa"],
              reference::resolve_isa(reference::default_embree_config()));
  }
}

TEST(ReferenceIsaCli, TheOptionOverridesTheExperiment) {
  IsaFolder f;
  const auto r = run_cli("run " + f.config("4", R"(,"embree_config":"isa=sse4.2")") +
                         " --quiet --embree-config isa=sse2 --out " + (f.dir / "o").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(f.record("o")["reference"]["embree_isa"], "sse2");
  EXPECT_EQ(f.record("o")["reference"]["embree_config"], "isa=sse2");
}

TEST(ReferenceIsaCli, AnIsaTheCpuLacksIsAnEnvironmentError) {
  std::string missing;
  for (const std::string& isa : reference::embree_isas())
    if (!reference::cpu_supports_isa(isa)) missing = isa;
  if (missing.empty()) GTEST_SKIP() << "this CPU runs every Embree ISA";
  IsaFolder f;
  const auto r = run_cli("run " + f.config("4", R"(,"embree_config":"isa=)" + missing + "\"") +
                         " --quiet --out " + (f.dir / "o").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("this CPU supports at most " + reference::best_cpu_isa()),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(f.dir / "o" / "results.jsonl")) << "no job may run";
}

TEST(ReferenceIsaCli, AMalformedChoiceIsBadInput) {
  IsaFolder f;
  const auto r = run_cli("run " + f.config("4") + " --embree-config threads=2 --out " +
                         (f.dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--embree-config"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sb::test
