// `shadowbench new-technique NAME`: which names it takes, and that it never
// writes into a folder that exists, and which template it writes. Building
// and running what it writes is tests/out_of_tree/scaffold_build_and_run.py
// and default_scaffold_on_masked_scenes.py.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../config/cli_runner.h"
#include "cli/new_technique.h"

namespace sb::test {

using plugin::Needs;
using plugin::Registry;

namespace {

namespace fs = std::filesystem;

Registry registry_with(const std::string& technique) {
  Registry r;
  r.add({technique, "family_of_" + technique, "a stand-in", Needs{}, {}, nullptr});
  return r;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A fresh folder under the test's temporary directory.
fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(testing::TempDir()) / ("new_technique_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(NewTechnique, TakesLowercaseCIdentifiersNoTechniqueHas) {
  const Registry r = registry_with("pcf_box");
  for (const char* name : {"my_pcf", "a", "pcss2", "soft_shadow_v3", "pcf_box_mine"})
    EXPECT_EQ(cli::technique_name_problem(name, r), "") << name;
}

TEST(NewTechnique, RefusesNamesThatAreNotLowercaseCIdentifiersAndSaysWhy) {
  const Registry r = registry_with("pcf_box");
  struct {
    std::string name;
    const char* says;
  } cases[] = {
      {"", "NAME is empty"},
      {"1pcf", "NAME '1pcf' does not start with a lowercase letter"},
      {"_pcf", "NAME '_pcf' does not start with a lowercase letter"},
      {"MyPcf", "NAME 'MyPcf' does not start with a lowercase letter"},
      {"my-pcf", "NAME 'my-pcf' has the character '-'"},
      {"myPcf", "NAME 'myPcf' has the character 'P'"},
      {"my pcf", "NAME 'my pcf' has the character ' '"},
      {"my/pcf", "NAME 'my/pcf' has the character '/'"},
      {"my__pcf", "NAME 'my__pcf' has \"__\""},
      {std::string(49, 'a'), "has 49 characters; at most 48"},
      {"class", "NAME 'class' is a C++ keyword"},
      {"and", "NAME 'and' is a C++ keyword"},
  };
  for (const auto& c : cases)
    EXPECT_NE(cli::technique_name_problem(c.name, r).find(c.says), std::string::npos)
        << c.name << ": " << cli::technique_name_problem(c.name, r);
}

TEST(NewTechnique, RefusesTheNameOfATechniqueTheRegistryHas) {
  EXPECT_EQ(cli::technique_name_problem("pcf_box", registry_with("pcf_box")),
            "NAME 'pcf_box' is a technique already (family family_of_pcf_box); choose another "
            "name");
}

// `new-technique NAME` into dir/out exits 2 with an error that starts
// "NAME 'NAME'" + `says`, and writes nothing.
void expect_refused(const fs::path& dir, const std::string& name, const std::string& says = "") {
  const fs::path folder = dir / "out";
  const auto r = run_cli("new-technique " + name + " --dir " + folder.string());
  EXPECT_EQ(r.exit_code, 2) << name << "\n" << r.output;
  EXPECT_NE(
      r.output.find("shadowbench: error: <input>: at command line: NAME '" + name + "'" + says),
      std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(folder)) << name;
}

TEST(NewTechnique, TheCommandRefusesABuiltInsNameOrABadOneWithExitTwoAndWritesNothing) {
  const fs::path dir = scratch("bad_names");
  for (const char* name : {"pcf_box", "shadow_map", "my-pcf", "1pcf"}) expect_refused(dir, name);
}

// CMake's reserved target names (policy CMP0037: its documentation names all,
// clean, help, install, and test and package with CTest or CPack; CMake 3.25
// also refused preinstall, edit_cache, rebuild_cache and package_source when
// tried): NAME is the plugin's target, so each made a project CMake refused.
TEST(NewTechnique, TheCommandRefusesTargetNamesCMakeReservesWithExitTwoAndWritesNothing) {
  const fs::path dir = scratch("cmake_reserved");
  for (const char* name : {"all", "clean", "help", "install", "test", "package", "preinstall",
                           "edit_cache", "rebuild_cache", "package_source"})
    expect_refused(dir, name, " is a target name CMake reserves");
  // Names that only contain a reserved one are fine.
  for (const char* name : {"all_pcf", "my_test", "cleaner"})
    EXPECT_EQ(cli::technique_name_problem(name, Registry{}), "") << name;
}

TEST(NewTechnique, WritesEveryFileOfTheTemplateWithTheName) {
  const fs::path folder = scratch("writes") / "my_soft";
  const auto r = run_cli("new-technique my_soft --dir " + folder.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"my_soft.cpp", "CMakeLists.txt", "my_soft.json", "README.md"}) {
    ASSERT_TRUE(fs::is_regular_file(folder / file)) << file << "\n" << r.output;
    const std::string text = read_file(folder / file);
    EXPECT_EQ(text.find('@'), std::string::npos) << file << " keeps a placeholder:\n" << text;
    EXPECT_NE(text.find("my_soft"), std::string::npos) << file;
  }
  EXPECT_NE(
      read_file(folder / "CMakeLists.txt").find("shadowbench_add_plugin(my_soft my_soft.cpp)"),
      std::string::npos);
}

// The default is the kit's template, which honours alpha masks (no
// opaque_casters need, so masked scenes run it); --bare writes the plugin-API
// one, which declares opaque_casters. Running the default on foliage:
// tests/out_of_tree/default_scaffold_on_masked_scenes.py.
TEST(NewTechnique, TheDefaultIsTheKitTemplateAndBareThePluginApiOne) {
  const fs::path kit = scratch("default") / "my_soft";
  ASSERT_EQ(run_cli("new-technique my_soft --dir " + kit.string()).exit_code, 0);
  EXPECT_NE(read_file(kit / "CMakeLists.txt").find("shadowbench::shadow_kit"), std::string::npos);
  EXPECT_EQ(read_file(kit / "my_soft.cpp").find("kOpaqueCasters"), std::string::npos);
  const fs::path bare = scratch("bare") / "my_soft";
  ASSERT_EQ(run_cli("new-technique my_soft --bare --dir " + bare.string()).exit_code, 0);
  EXPECT_EQ(read_file(bare / "CMakeLists.txt").find("shadow_kit"), std::string::npos);
  EXPECT_NE(read_file(bare / "my_soft.cpp").find("kOpaqueCasters"), std::string::npos);
  // --bare is --family plugin_api: both at once is refused.
  const fs::path both = scratch("both") / "my_soft";
  const auto r = run_cli("new-technique my_soft --bare --family shadow_map --dir " + both.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(both));
}

TEST(NewTechnique, NeverWritesIntoAFolderThatExists) {
  const fs::path folder = scratch("exists") / "my_soft";
  fs::create_directories(folder);
  std::ofstream(folder / "my_soft.cpp") << "// the user's own work\n";
  const auto r = run_cli("new-technique my_soft --dir " + folder.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(folder.string() + ": exists already; new-technique writes a new folder "
                                            "and never overwrites"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(folder / "my_soft.cpp"), "// the user's own work\n");
  EXPECT_FALSE(fs::exists(folder / "CMakeLists.txt"));
  // An empty folder, or a file of that name, is refused alike.
  const fs::path empty = scratch("exists_empty") / "empty";
  fs::create_directories(empty);
  EXPECT_EQ(run_cli("new-technique my_soft --dir " + empty.string()).exit_code, 2);
  EXPECT_TRUE(fs::is_empty(empty));
  const fs::path file = scratch("exists_file") / "a_file";
  std::ofstream(file) << "x";
  EXPECT_EQ(run_cli("new-technique my_soft --dir " + file.string()).exit_code, 2);
  EXPECT_EQ(read_file(file), "x");
}

}  // namespace
}  // namespace sb::test
