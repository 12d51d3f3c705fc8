#include "plugin/registry.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace sb {

bool Needs::has(const std::string& name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void Registry::add(TechniqueInfo info) {
  if (find(info.name) != nullptr)
    throw std::logic_error("technique '" + info.name + "' registered twice");
  techniques_.push_back(std::move(info));
}

const TechniqueInfo* Registry::find(const std::string& name) const {
  for (const auto& t : techniques_)
    if (t.name == name) return &t;
  return nullptr;
}

void Registry::add_provider(NeedProvider provider) {
  if (find_provider(provider.name) != nullptr)
    throw std::logic_error("need '" + provider.name + "' provided twice");
  providers_.push_back(std::move(provider));
}

const NeedProvider* Registry::find_provider(const std::string& name) const {
  for (const auto& p : providers_)
    if (p.name == name) return &p;
  return nullptr;
}

int Registry::load_plugins(const std::string& dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir)) throw std::runtime_error("plugin folder not found: " + dir);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".so") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // stable order for `list` and plans
  for (const auto& f : files) {
    void* handle = dlopen(f.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr)
      throw std::runtime_error("cannot load plugin " + f.string() + ": " + dlerror());
    using Entry = void (*)(Registry&);
    auto entry = reinterpret_cast<Entry>(dlsym(handle, "shadowbench_register_plugin"));
    if (entry == nullptr)
      throw std::runtime_error("plugin " + f.string() + " has no shadowbench_register_plugin");
    entry(*this);
    modules_.push_back(handle);
  }
  return static_cast<int>(files.size());
}

std::string default_plugin_dir() {
  if (const char* env = std::getenv("SHADOWBENCH_PLUGIN_DIR"); env != nullptr && *env != '\0')
    return env;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto dir = exe.parent_path() / "plugins";
    if (std::filesystem::is_directory(dir)) return dir.string();
  }
#ifdef SHADOWBENCH_DEFAULT_PLUGIN_DIR
  return SHADOWBENCH_DEFAULT_PLUGIN_DIR;
#else
  return "plugins";
#endif
}

}  // namespace sb
