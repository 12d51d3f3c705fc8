// A library opened on first use (core/lazy_library.h): a missing library or
// symbol is an error that names the path and the dynamic linker's words,
// not a crash; and the image codec module is found beside
// libshadowbench_core.so, as installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/image_codec.h"
#include "core/lazy_library.h"

namespace sb::test {
namespace {

std::string error_of(core::LazyLibrary& library, const char* symbol) {
  try {
    library.symbol(symbol);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(LazyLibrary, AMissingLibraryIsAnErrorNamingItsPathAndWhy) {
  core::LazyLibrary missing("/nonexistent/libmissing.so", "the missing library");
  const std::string first = error_of(missing, "f");
  EXPECT_NE(first.find("cannot load the missing library (/nonexistent/libmissing.so)"),
            std::string::npos)
      << first;
  EXPECT_NE(first.find("No such file or directory"), std::string::npos) << first;
  EXPECT_EQ(error_of(missing, "f"), first) << "opened once: the same error every time";
}

TEST(LazyLibrary, AMissingSymbolIsAnErrorNamingIt) {
  core::LazyLibrary libc("libc.so.6", "the C library");
  EXPECT_NE(libc.symbol("strlen"), nullptr);
  const std::string error = error_of(libc, "shadowbench_no_such_symbol");
  EXPECT_NE(error.find("the C library (libc.so.6) lacks shadowbench_no_such_symbol"),
            std::string::npos)
      << error;
}

TEST(LazyLibrary, TheImageCodecModuleLiesBesideTheCoreLibrary) {
  const std::filesystem::path module = core::image_codec_path();
  EXPECT_EQ(module.filename(), "libshadowbench_image_codec.so");
  EXPECT_TRUE(std::filesystem::exists(module.parent_path() / "libshadowbench_core.so")) << module;
  EXPECT_TRUE(std::filesystem::exists(module)) << module;
}

}  // namespace
}  // namespace sb::test
