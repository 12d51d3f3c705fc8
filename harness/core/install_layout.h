#pragma once
// Where shadowbench finds its plugins and its shared data (plot_charts.py,
// the example configs), relative to its own executable, so that a build
// tree, an installed prefix and a moved prefix all work without settings:
//   build tree:  <build>/shadowbench, <build>/plugins, <build>/share/shadowbench
//   installed:   <prefix>/bin/shadowbench, <prefix>/lib/shadowbench/plugins,
//                <prefix>/share/shadowbench, <prefix>/share/doc/shadowbench
// Environment variables override or add (docs/install.md).
#include <string>
#include <vector>

namespace sb::core {

// The running executable's folder; "" when /proc/self/exe cannot be read.
std::string executable_dir();

// The technique plugins' folder: $SHADOWBENCH_PLUGIN_DIR; else <exe>/plugins
// when it exists (a build tree); else the installed folder relative to <exe>
// (<prefix>/lib/shadowbench/plugins), whether it exists or not.
std::string default_plugin_dir();

// More plugin folders, loaded after the default one: $SHADOWBENCH_PLUGIN_PATH,
// ':'-separated like PATH (empty entries are skipped).
std::vector<std::string> extra_plugin_dirs();

// The folders searched for shared data, in order: $SHADOWBENCH_SHARE_DIR,
// <exe>/share/shadowbench (a build tree), <exe>/../share/shadowbench (an
// installed prefix). The last two only when they exist.
std::vector<std::string> data_dirs();

// A document of docs/ ("install.md") as a message names it: where the
// reader has it. Installed (<exe>/../share/doc/shadowbench/NAME exists), its
// full path there; else (a build tree, a moved binary) "docs/NAME", the
// source's. Every message that names a doc says it through this.
std::string doc_path(const std::string& name);

}  // namespace sb::core
