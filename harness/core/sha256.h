#pragma once
// SHA-256 (OpenSSL's EVP), as lowercase hex: the content hash of a plugin
// module or of the harness's own binaries in a record (docs/results.md,
// technique.plugin and build), where FNV-1a (core/hash.h) is too weak to
// name a file's bytes.
#include <optional>
#include <string>
#include <string_view>

namespace sb::core {

// 64 lowercase hex digits of SHA-256 over `bytes`.
std::string sha256_hex(std::string_view bytes);

// SHA-256 of a regular file's bytes, read in blocks; nullopt when it is not
// a regular file (a device such as /dev/zero would never end, a FIFO could
// block) or cannot be read.
std::optional<std::string> sha256_file_hex(const std::string& path);

}  // namespace sb::core
