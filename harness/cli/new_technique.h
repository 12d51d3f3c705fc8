#pragma once
// `shadowbench new-technique`: a buildable plugin folder from a template
// (cli/technique_template.h), for a name checked first.
#include <map>
#include <string>
#include <vector>

#include "cli/technique_template.h"
#include "plugin/registry.h"

namespace sb::cli {

// "" when `name` can name a new technique, else why not: it must be a
// lowercase C identifier (a-z, 0-9 and '_', starting with a letter, no "__",
// at most 48 characters), not a C++ keyword (it names a namespace and a
// CMake target), and no technique `registry` knows.
std::string technique_name_problem(const std::string& name, const plugin::Registry& registry);

// Writes `tmpl`'s files into `folder` with @NAME@ and `values` (placeholder
// -> text) filled in, and returns the paths written. Throws InputError,
// writing nothing, when `folder` exists (even empty: it may be someone's).
std::vector<std::string> write_technique_folder(const TechniqueTemplate& tmpl,
                                                const std::string& name,
                                                const std::map<std::string, std::string>& values,
                                                const std::string& folder);

}  // namespace sb::cli
