#pragma once
// Which plugin module a technique came from, as a record names it
// (technique.plugin, docs/results.md): the .so's name in its plugin folder,
// its size and SHA-256, and the plugin API version. A rebuilt plugin has
// another hash, so a rerun into the same folder runs its jobs again
// (run/job_identity.h) and `compare` says that the plugins differ.
#include <cstdint>
#include <string>

namespace sb::plugin {

// The plugin API's version: the contract of plugin/ (Technique, FrameInputs,
// needs, TechniqueInfo, Registry) as compiled into a module. Bump it with
// every change of that ABI.
// 2: TechniqueInfo::needs_of_params; 3: ParamSpec::map_size; 4: the names
// live in their folders' namespaces (sb::core::Scene, sb::plugin::Technique,
// sb::gl::GpuScene), so modules built before do not load; their source builds
// unchanged, the names being kept in sb too (plugin/api_names.h); 5:
// ParamSpec::decides and Scene::inputs (a job's identity by what it reads)
inline constexpr int kPluginApiVersion = 5;

struct PluginIdentity {
  std::string file;       // relative to the plugin folder it was loaded from: "shadow_map.so"
  std::int64_t size = 0;  // bytes
  std::string sha256;     // of its bytes, 64 hex digits ("" when it could not be read)
  int api_version = kPluginApiVersion;
};

// The identity of the module at `path`, read once; never throws.
PluginIdentity identify_plugin(const std::string& path);

}  // namespace sb::plugin
