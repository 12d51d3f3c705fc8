#pragma once
// The content hashes of the harness's own code, for record["build"]: the
// build fingerprint names the compiler and flags, not the code, so a
// rebuilt harness would otherwise resume records of the old one.
#include <string>

namespace sb::run {

struct CodeIdentity {
  // SHA-256 of each file's bytes; "" when it could not be found or read.
  std::string driver_sha256;      // this process's executable (/proc/self/exe)
  std::string core_sha256;        // libshadowbench_core.so, as loaded
  std::string plugin_api_sha256;  // libshadowbench_plugin_api.so, as loaded
};

// This process's code, hashed once (the first call reads the files).
const CodeIdentity& this_code();

}  // namespace sb::run
