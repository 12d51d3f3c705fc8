// shadowbench new-technique NAME: a plugin folder that builds against this
// shadowbench and runs beside the built-ins it is nearest to.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/new_technique.h"
#include "cli/options.h"
#include "cli/shared.h"
#include "cli/technique_template.h"
#include "core/error.h"
#include "core/install_layout.h"

namespace sb::cli {

using core::executable_dir;
using core::InputError;
using core::kExitOk;
using plugin::Registry;

namespace {

namespace fs = std::filesystem;

// How CMake finds this shadowbench's plugin API: a build folder has
// shadowbenchConfig.cmake beside the executable, an installed prefix under
// lib/shadowbench/cmake (cmake/install.cmake).
std::string cmake_hint(const std::string& exe_dir) {
  std::error_code ec;
  if (!exe_dir.empty() && fs::exists(fs::path(exe_dir) / "shadowbenchConfig.cmake", ec))
    return "-Dshadowbench_DIR=" + exe_dir;
  const fs::path prefix = fs::path(exe_dir).parent_path();
  if (!exe_dir.empty() &&
      fs::exists(prefix / "lib" / "shadowbench" / "cmake" / "shadowbenchConfig.cmake", ec))
    return "-DCMAKE_PREFIX_PATH=" + prefix.string();
  return "-DCMAKE_PREFIX_PATH=/path/to/shadowbench/prefix";
}

struct NewTechniqueArgs {
  std::string new_name;
  std::string family = technique_templates().front().family;  // the template
  bool bare = false;                                          // --bare: --family plugin_api
  std::string dir;                                            // the folder (default: NAME)
  std::string plugins;
};

int cmd_new_technique(const NewTechniqueArgs& a) {
  const TechniqueTemplate* tmpl = find_technique_template(a.bare ? "plugin_api" : a.family);
  if (tmpl == nullptr)  // the parser's choice check lists the families
    throw InputError("", "command line", "no template for --family '" + a.family + "'");
  const Registry registry = load_registry(a.plugins);
  if (const std::string problem = technique_name_problem(a.new_name, registry); !problem.empty())
    throw InputError("", "command line", problem);
  const std::string folder = a.dir.empty() ? a.new_name : a.dir;
  const std::string exe_dir = executable_dir();
  const std::map<std::string, std::string> values = {
      {"@CMAKE_HINT@", cmake_hint(exe_dir)},
      {"@SHADOWBENCH@", exe_dir.empty() ? "shadowbench" : exe_dir + "/shadowbench"}};
  for (const std::string& path : write_technique_folder(*tmpl, a.new_name, values, folder))
    std::printf("wrote %s\n", path.c_str());
  std::printf("%s (%s): build, load and run it as %s/README.md says.\n", a.new_name.c_str(),
              tmpl->summary.c_str(), folder.c_str());
  return kExitOk;
}

}  // namespace

void add_new_technique_command(CommandLine& cl) {
  const auto a = std::make_shared<NewTechniqueArgs>();
  CLI::App* new_technique = cl.add_command(
      cl.app(), "new-technique",
      "Write a plugin folder for a new technique NAME: its source (a working shadow map with PCF "
      "on the shadow-map kit, fair on alpha-masked scenes, to start from), CMakeLists.txt, a "
      "config that runs it beside its nearest built-ins, and a README with the commands to "
      "build, load and run it.",
      "shadowbench new-technique my_pcf --dir ~/my_pcf", [a] { return cmd_new_technique(*a); });
  add_argument(new_technique, "NAME", a->new_name,
               "the technique's name: a lowercase C identifier no plugin uses")
      ->required();
  std::vector<std::string> families;
  std::string family_doc = "the template:";
  for (const TechniqueTemplate& t : technique_templates()) {
    families.push_back(t.family);
    family_doc += (families.size() == 1 ? " " : "; ") + t.family + ", " + t.summary;
  }
  CLI::Option* family = add_choice(new_technique, "--family", a->family, families, family_doc);
  // The bare template declares opaque_casters: every alpha-masked scene
  // skips it, so it is asked for by name, never the default.
  new_technique
      ->add_flag("--bare", a->bare,
                 "write the bare template (--family plugin_api) instead: its own light frustum, "
                 "depth pass and lookup on the plugin API alone, skipped on alpha-masked scenes")
      ->excludes(family);
  new_technique
      ->add_option("--dir", a->dir, "the folder to write, which must not exist (default: NAME)")
      ->type_name("DIR");
  add_plugins(new_technique, a->plugins);
}

}  // namespace sb::cli
