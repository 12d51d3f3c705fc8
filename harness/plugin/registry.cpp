#include "plugin/registry.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/install_layout.h"

namespace sb::plugin {

namespace {

// dlerror()'s words, and when the module names a shadowbench symbol this
// build does not define (a mangled name in sb: "_ZN2sb...", "_ZNK2sb...",
// "_ZTVN2sb..."), what that most likely means: it was built against another
// plugin API version, whose names this build lacks.
std::string dlopen_failure(const char* why) {
  std::string out = why != nullptr ? why : "dlopen failed";
  const std::string marker = "undefined symbol: _Z";
  const size_t at = out.find(marker);
  if (at != std::string::npos) {
    size_t name = at + marker.size();  // past the mangling's capitals: N, K, TV, TI
    while (name < out.size() && std::isupper(static_cast<unsigned char>(out[name])) != 0) ++name;
    if (out.compare(name, 3, "2sb") == 0)
      out +=
          " (a shadowbench symbol this build lacks: the module was most likely built against "
          "another plugin API version; this build's is " +
          std::to_string(kPluginApiVersion) +
          ". Rebuild it against this shadowbench: " + core::doc_path("writing_a_technique.md") +
          ", \"Version\")";
  }
  return out;
}

}  // namespace

bool Needs::has(const std::string& name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void Registry::add(TechniqueInfo info) {
  if (find(info.name) != nullptr) {
    const std::string& first = origins_[info.name];
    throw std::logic_error("technique '" + info.name + "' registered twice" +
                           (first.empty() ? std::string() : ", first by " + first));
  }
  // A switch the stability suite reads must be one of the technique's own
  // Bool or Choice parameters.
  for (const core::ParamSpec& p : info.params) {
    if (p.enabled_by.empty()) continue;
    const auto sw = std::find_if(info.params.begin(), info.params.end(),
                                 [&](const core::ParamSpec& q) { return q.name == p.enabled_by; });
    if (sw == info.params.end() ||
        (sw->type != core::ParamType::Bool && sw->type != core::ParamType::Choice))
      throw std::logic_error("technique '" + info.name + "': parameter '" + p.name +
                             "' is enabled by '" + p.enabled_by +
                             "', which is not a bool or choice parameter of it");
  }
  origins_[info.name] = loading_;
  if (!loading_.empty() && identities_.count(loading_) == 0)
    identities_.emplace(loading_, identify_plugin(loading_));
  techniques_.push_back(std::move(info));
}

const PluginIdentity* Registry::plugin_of(const std::string& technique) const {
  const auto origin = origins_.find(technique);
  if (origin == origins_.end()) return nullptr;
  const auto id = identities_.find(origin->second);
  return id == identities_.end() ? nullptr : &id->second;
}

const TechniqueInfo* Registry::find(const std::string& name) const {
  for (const auto& t : techniques_)
    if (t.name == name) return &t;
  return nullptr;
}

void Registry::add_provider(NeedProvider provider) {
  if (find_provider(provider.name) != nullptr) {
    const std::string& first = origins_["need " + provider.name];
    throw std::logic_error("need '" + provider.name + "' provided twice" +
                           (first.empty() ? std::string() : ", first by " + first));
  }
  origins_["need " + provider.name] = loading_;
  providers_.push_back(std::move(provider));
}

const NeedProvider* Registry::find_provider(const std::string& name) const {
  for (const auto& p : providers_)
    if (p.name == name) return &p;
  return nullptr;
}

std::string Registry::register_module(const std::string& file, void (*entry)(Registry&)) {
  const size_t techniques = techniques_.size();
  const size_t providers = providers_.size();
  loading_ = file;
  std::string why;
  try {
    entry(*this);
  } catch (const std::exception& e) {
    // A technique or need another module registered (std::logic_error)
    // lands here too: the module loaded first keeps it, this one fails.
    why = e.what();
  } catch (...) {
    why = "threw a non-standard exception while registering";
  }
  loading_.clear();
  if (why.empty()) return why;
  // Half a module is no module: take back what it registered before the throw.
  techniques_.erase(techniques_.begin() + std::ptrdiff_t(techniques), techniques_.end());
  providers_.erase(providers_.begin() + std::ptrdiff_t(providers), providers_.end());
  std::erase_if(origins_, [&file](const auto& origin) { return origin.second == file; });
  return why;
}

int Registry::load_plugins(const std::string& dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir)) throw std::runtime_error("plugin folder not found: " + dir);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".so") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // stable order for `list` and plans
  int loaded = 0;
  for (const auto& f : files) {
    // The same module reached twice (a folder named in two places) is loaded once.
    std::error_code ec;
    const std::string canonical = fs::canonical(f, ec).string();
    if (!ec &&
        std::find(module_paths_.begin(), module_paths_.end(), canonical) != module_paths_.end())
      continue;
    if (std::any_of(failures_.begin(), failures_.end(), [&](const PluginLoadFailure& failed) {
          std::error_code ec2;
          return fs::canonical(failed.file, ec2).string() == canonical && !ec2;
        }))
      continue;  // and a failed one fails once
    void* handle = dlopen(f.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      failures_.push_back({f.string(), dlopen_failure(dlerror())});
      continue;
    }
    using Entry = void (*)(Registry&);
    auto entry = reinterpret_cast<Entry>(dlsym(handle, "shadowbench_register_plugin"));
    if (entry == nullptr) {
      failures_.push_back({f.string(), "no shadowbench_register_plugin (is it a plugin?)"});
      dlclose(handle);
      continue;
    }
    if (std::string why = register_module(f.string(), entry); !why.empty()) {
      // Its code ran (and may own what it registered): never unloaded.
      failures_.push_back({f.string(), why});
      continue;
    }
    modules_.push_back(handle);
    module_paths_.push_back(ec ? f.string() : canonical);
    ++loaded;
  }
  return loaded;
}

}  // namespace sb::plugin
