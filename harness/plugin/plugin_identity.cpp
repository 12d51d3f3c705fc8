#include "plugin/plugin_identity.h"

#include <filesystem>
#include <stdexcept>

#include "core/sha256.h"

namespace sb::plugin {

using core::sha256_file_hex;

PluginIdentity identify_plugin(const std::string& path) {
  namespace fs = std::filesystem;
  PluginIdentity id;
  // Plugins are loaded from the top of their folder only, so the name is
  // the path relative to it.
  id.file = fs::path(path).filename().string();
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!ec) id.size = std::int64_t(size);
  try {
    id.sha256 = sha256_file_hex(path).value_or("");
  } catch (const std::runtime_error&) {
    // No digest (OpenSSL failed): an empty hash, which a rerun treats as a change.
  }
  return id;
}

}  // namespace sb::plugin
