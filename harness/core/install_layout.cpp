#include "core/install_layout.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace sb::core {
namespace fs = std::filesystem;

namespace {

// Set by CMake from GNUInstallDirs: the installed folders relative to the
// installed executable's folder.
#ifndef SHADOWBENCH_BIN_TO_PLUGINS
#define SHADOWBENCH_BIN_TO_PLUGINS "../lib/shadowbench/plugins"
#endif
#ifndef SHADOWBENCH_BIN_TO_DATA
#define SHADOWBENCH_BIN_TO_DATA "../share/shadowbench"
#endif
#ifndef SHADOWBENCH_BIN_TO_DOC
#define SHADOWBENCH_BIN_TO_DOC "../share/doc/shadowbench"
#endif

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value == nullptr ? std::string() : std::string(value);
}

bool folder_exists(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

}  // namespace

std::string executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

std::string default_plugin_dir() {
  if (std::string env = environment("SHADOWBENCH_PLUGIN_DIR"); !env.empty()) return env;
  const fs::path exe = executable_dir();
  const fs::path installed = (exe / SHADOWBENCH_BIN_TO_PLUGINS).lexically_normal();
  if (folder_exists(exe / "plugins")) return (exe / "plugins").string();
  // No compiled-in fallback: a moved or copied binary must not quietly load
  // some build tree's plugins. A missing folder is reported by load_plugins.
  return installed.string();
}

std::vector<std::string> extra_plugin_dirs() {
  std::vector<std::string> dirs;
  const std::string path = environment("SHADOWBENCH_PLUGIN_PATH");
  size_t start = 0;
  while (start <= path.size()) {
    const size_t end = std::min(path.find(':', start), path.size());
    if (end > start) dirs.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return dirs;
}

std::vector<std::string> data_dirs() {
  std::vector<std::string> dirs;
  if (std::string env = environment("SHADOWBENCH_SHARE_DIR"); !env.empty()) dirs.push_back(env);
  if (const std::string exe = executable_dir(); !exe.empty()) {
    for (const fs::path& candidate :
         {fs::path(exe) / "share" / "shadowbench", (fs::path(exe) / SHADOWBENCH_BIN_TO_DATA)})
      if (folder_exists(candidate)) dirs.push_back(candidate.lexically_normal().string());
  }
  return dirs;
}

std::string doc_path(const std::string& name) {
  if (const std::string exe = executable_dir(); !exe.empty()) {
    const fs::path installed = (fs::path(exe) / SHADOWBENCH_BIN_TO_DOC / name).lexically_normal();
    std::error_code ec;
    if (fs::is_regular_file(installed, ec)) return installed.string();
  }
  return "docs/" + name;
}

}  // namespace sb::core
