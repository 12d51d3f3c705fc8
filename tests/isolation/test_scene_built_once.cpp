// A run builds each scene once, whatever its isolation: the plan's build is
// the one its jobs render, in the parent (--isolation none) or in forked
// children, which inherit it (issue 65). Counted from outside the program:
// the kernel reports each open of the scene's glTF file (inotify), and a
// run's opens are compared with those of one load of the file.
#include <gtest/gtest.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <string>

#include "isolation_util.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;

// The opens of `file` while `command` runs (each open is followed by its
// close, so no two open events in a row are merged into one).
int opens_while(const fs::path& file, const std::string& command, CliRun* out = nullptr) {
  const int fd = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd < 0) throw std::runtime_error("inotify_init1 failed");
  const int watch = ::inotify_add_watch(fd, file.c_str(), IN_OPEN | IN_CLOSE);
  if (watch < 0) {
    ::close(fd);
    throw std::runtime_error("cannot watch " + file.string());
  }
  const CliRun r = run_command(command);
  if (out != nullptr) *out = r;
  int opens = 0;
  alignas(inotify_event) std::array<char, 1 << 16> buf{};
  for (;;) {
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n <= 0) break;  // EAGAIN: every event read
    for (ssize_t at = 0; at < n;) {
      const auto* ev = reinterpret_cast<const inotify_event*>(buf.data() + at);
      if (ev->wd == watch && (ev->mask & IN_OPEN) != 0) ++opens;
      at += ssize_t(sizeof(inotify_event) + ev->len);
    }
  }
  ::close(fd);
  return opens;
}

class SceneBuiltOnce : public ::testing::TestWithParam<const char*> {};

TEST_P(SceneBuiltOnce, ARunOfOneSceneAndTwoTechniquesBuildsItOnce) {
  const fs::path dir = test_folder();
  const fs::path glb = dir / "scene.glb";
  const CliRun exported =
      run_command("'" SHADOWBENCH_EXE "' scene export sphere_grid:grid=2 '" + glb.string() + "'");
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  // What one build of the scene opens (the loader may open the file more
  // than once).
  const int one_build = opens_while(glb, "'" SHADOWBENCH_EXE "' scene info '" + glb.string() + "'");
  ASSERT_GE(one_build, 1);

  nlohmann::json config = small_experiment(nlohmann::json::array({"shadow_map", "shadow_volume"}));
  config["scenes"] = nlohmann::json::array(
      {{{"type", "gltf"}, {"label", "counted"}, {"params", {{"file", "scene.glb"}}}}});
  const std::string path = write_config(dir, config);
  CliRun run;
  const int opens = opens_while(
      glb,
      shadowbench_command("run '" + path + "' --out '" + (dir / "out").string() + "' --isolation " +
                          GetParam() + " --no-cache --no-images --quiet"),
      &run);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto records = jsonl_records(dir / "out");
  ASSERT_EQ(records.size(), 2u);
  for (const auto& r : records) EXPECT_EQ(r["status"], "ok") << r.dump();
  // Before issue 65 the parent built the scene to plan and again to run
  // (none), or each child built it again (group: 2, job: 3 builds).
  EXPECT_EQ(opens, one_build) << "the run built the scene " << double(opens) / one_build
                              << " times";
}

INSTANTIATE_TEST_SUITE_P(EveryIsolation, SceneBuiltOnce, ::testing::Values("none", "group", "job"));

}  // namespace
}  // namespace sb::test
