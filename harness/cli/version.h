#pragma once
// `shadowbench --version`: the version, `git describe` of the source it was
// built from, the GL backends built in, and the folders plugins and data are
// found in (core/install_layout.h), so a report of a problem says all four.
#include <string>

namespace sb::cli {

std::string version_text();

}  // namespace sb::cli
