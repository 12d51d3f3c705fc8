// A run opens what the printing commands never load (tests/cli/
// test_lazy_libraries.cpp): the GL backend's library when it creates a
// context and the image codec module, with OpenImageIO, when it writes the
// images; and the images are there. LD_DEBUG_OUTPUT also logs the forked
// children, whose stderr the driver keeps to itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/cli_run.h"
#include "e2e_util.h"
#include "metrics/image_io.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Every log the dynamic linker wrote under `prefix` (one file per exec'd process).
std::string loader_logs(const fs::path& folder) {
  std::string all;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename().string().rfind("ld.", 0) != 0) continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    all += text.str();
  }
  return all;
}

TEST(LazyLibraries, ARunLoadsTheBackendAndTheImageCodecWhenItNeedsThem) {
  const fs::path dir = fresh_test_folder("lazy_libraries_run");
  const json config = {{"name", "lazy"},
                       {"scenes", json::array({small_scene(1.0)})},
                       {"techniques", json::array({"none"})},
                       {"resolutions", json::array({json::array({64, 48})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 4}}}};
  std::ofstream(dir / "lazy.json") << config.dump();
  const CliRun r = run_command("LD_DEBUG=files LD_DEBUG_OUTPUT=" + (dir / "ld").string() + " " +
                               SHADOWBENCH_EXE + " run " + (dir / "lazy.json").string() +
                               " --out " + (dir / "run").string() + " --no-cache --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string log = loader_logs(dir);
  for (const char* library :
       {"libOSMesa.so.8", "libshadowbench_image_codec.so", "libOpenImageIO.so"})
    EXPECT_NE(log.find(library), std::string::npos) << "the run did not load " << library;
  EXPECT_NE(log.find("libshadowbench_image_codec.so [0];  dynamically loaded by"),
            std::string::npos)
      << "the codec module is opened, not linked";
  const auto records = jsonl_records(dir / "run");
  ASSERT_EQ(records.size(), 1u);
  const core::ImageF v = metrics::io::read_image(
      (dir / "run" / records[0]["images"]["visibility"].get<std::string>()).string());
  EXPECT_EQ(v.width, 64);
  EXPECT_EQ(v.height, 48);
}

// Planning a glTF scene decodes its textures in the parent, which loads
// OpenImageIO there, and with it log4cplus's four idle threads: the parent
// still forks its children (core::threads_started_by_lazy_libraries()).
TEST(LazyLibraries, ThreadsOfALibraryLoadedBeforeTheChildrenDoNotStopIsolation) {
  const fs::path dir = fresh_test_folder("lazy_libraries_textures");
  const std::string glb = (dir / "leaves.glb").string();
  const CliRun exported =
      run_command(std::string(SHADOWBENCH_EXE) + " scene export foliage " + glb);
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  ASSERT_NE(exported.output.find("1 textures"), std::string::npos) << exported.output;
  const json config = {{"name", "textures"},
                       {"scenes", json::array({{{"type", "gltf"}, {"params", {{"file", glb}}}}})},
                       {"techniques", json::array({"none"})},
                       {"resolutions", json::array({json::array({64, 48})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 4}}}};
  std::ofstream(dir / "textures.json") << config.dump();
  const CliRun r =
      run_command(std::string(SHADOWBENCH_EXE) + " run " + (dir / "textures.json").string() +
                  " --out " + (dir / "run").string() + " --isolation group --no-cache --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto records = jsonl_records(dir / "run");
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0]["status"], "ok") << records[0].dump();
}

}  // namespace
}  // namespace sb::test
