// The commands that only print (--version, --help, completion) and those
// that read a config without images (validate) load neither OpenImageIO nor
// a GL backend: those are opened on first use (core/lazy_library.h), which
// keeps a process start near 10 ms instead of ~0.5 s. The dynamic linker
// says which files it loads (LD_DEBUG=files); a test, not a timing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../common/cli_run.h"

namespace sb::test {
namespace {

// The libraries a process start must not load.
const std::vector<std::string> kLoadedOnFirstUse = {
    "libshadowbench_image_codec.so", "libOpenImageIO.so", "libOSMesa.so", "libEGL.so", "libLLVM"};

// The dynamic linker's log of the files `args` loads, with the command's output.
CliRun run_logging_loads(const std::string& args) {
  return run_command("LD_DEBUG=files " + std::string(SHADOWBENCH_EXE) + " " + args);
}

void expect_none_loaded(const std::string& args) {
  const CliRun r = run_logging_loads(args);
  ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  // The log names every file it opens: the check would pass vacuously without it.
  ASSERT_NE(r.output.find("file=libshadowbench_core.so"), std::string::npos) << r.output;
  for (const std::string& library : kLoadedOnFirstUse)
    EXPECT_EQ(r.output.find(library), std::string::npos) << args << " loads " << library;
}

TEST(LazyLibraries, PrintingCommandsLoadNoImageCodecNorGl) {
  expect_none_loaded("--version");
  expect_none_loaded("--help");
  expect_none_loaded("completion bash");
}

TEST(LazyLibraries, ValidatingAConfigWithoutImagesLoadsNoImageCodecNorGl) {
  expect_none_loaded("validate " SHADOWBENCH_SOURCE_DIR "/configs/quick.json");
}

}  // namespace
}  // namespace sb::test
