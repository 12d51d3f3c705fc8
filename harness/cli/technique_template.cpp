#include "cli/technique_template.h"

namespace sb::cli {

const char* const kBuildLoadRun = R"(Build, load, run (from this folder):

    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release @CMAKE_HINT@ && cmake --build build
    export SHADOWBENCH_PLUGIN_PATH=$PWD/build
    @SHADOWBENCH@ run @NAME@.json --out results/@NAME@

The last command prints a table of every job's time and error against the
ray-traced reference; `results/@NAME@/` holds the records, tables and images.
)";

const std::vector<TechniqueTemplate>& technique_templates() {
  static const std::vector<TechniqueTemplate> templates = {shadow_map_template(),
                                                           plugin_api_template()};
  return templates;
}

const TechniqueTemplate* find_technique_template(const std::string& family) {
  for (const TechniqueTemplate& t : technique_templates())
    if (t.family == family) return &t;
  return nullptr;
}

}  // namespace sb::cli
