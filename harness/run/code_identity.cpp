#include "run/code_identity.h"

#include <dlfcn.h>

#include "core/sha256.h"
#include "plugin/plugin_identity.h"

namespace sb::run {

using core::sha256_file_hex;
using plugin::identify_plugin;

namespace {

// The shared object (or executable) that holds `address`.
std::string file_holding(const void* address) {
  Dl_info info{};
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) return "";
  return info.dli_fname;
}

std::string sha256_of(const std::string& path) {
  return path.empty() ? "" : sha256_file_hex(path).value_or("");
}

CodeIdentity hash_this_code() {
  CodeIdentity c;
  c.driver_sha256 = sha256_of("/proc/self/exe");
  // A function of each library locates its file, wherever it was loaded from.
  c.core_sha256 = sha256_of(file_holding(reinterpret_cast<const void*>(&this_code)));
  c.plugin_api_sha256 = sha256_of(file_holding(reinterpret_cast<const void*>(&identify_plugin)));
  return c;
}

}  // namespace

const CodeIdentity& this_code() {
  static const CodeIdentity kCode = hash_this_code();
  return kCode;
}

}  // namespace sb::run
