#pragma once
// The plugin folders `shadowbench new-technique` writes: one template per
// --family, each a list of files whose names and contents say @NAME@ where
// the technique's name goes. A template is one file in technique_templates/
// plus its line in technique_templates() (technique_template.cpp).
#include <string>
#include <vector>

namespace sb::cli {

struct TemplateFile {
  std::string path;     // relative to the new folder, e.g. "@NAME@.cpp"
  std::string content;  // with @NAME@ and the other placeholders below
};

// Placeholders besides @NAME@, filled from the running shadowbench:
//   @CMAKE_HINT@   how CMake finds this shadowbench's plugin API
//                  ("-Dshadowbench_DIR=<build>" or "-DCMAKE_PREFIX_PATH=<prefix>")
//   @SHADOWBENCH@  the command that runs it
struct TechniqueTemplate {
  std::string family;   // --family
  std::string summary;  // one line for --help
  std::vector<TemplateFile> files;
};

// The README's "Build, load, run" paragraph, the same in every template:
// tests/out_of_tree/scaffold_build_and_run.py runs its indented lines.
extern const char* const kBuildLoadRun;

// Every template, the default (--family's default: the kit's, fair on
// alpha-masked scenes) first.
const std::vector<TechniqueTemplate>& technique_templates();

// The template of one family; nullptr when there is none.
const TechniqueTemplate* find_technique_template(const std::string& family);

// One template per file of technique_templates/.
TechniqueTemplate plugin_api_template();
TechniqueTemplate shadow_map_template();

}  // namespace sb::cli
