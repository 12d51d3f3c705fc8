#pragma once
// The reference cache's file, <key>.sbref (reference.h: get()), in the
// host's byte order: an 8-byte magic, the file version, width, height, spp
// and seed, the method and the key (each length-prefixed), the visibility,
// standard-error and stop-bound images, the penumbra (a byte a pixel) and
// its source (length-prefixed), the adaptive reference's sample counts (no
// other method stores them), and an FNV-1a 64 checksum of all before it.
#include <filesystem>
#include <optional>
#include <string>

#include "reference/reference.h"

namespace sb::reference::detail {

// What a file must say to be the reference asked for.
struct CacheFileExpectation {
  std::string key;
  std::string method;
  int width = 0;
  int height = 0;
  int spp = 0;  // 0 for the exact reference
  uint64_t seed = 0;
  // Set for the adaptive reference, whose file holds each pixel's sample
  // count, none above this; unset for the others, whose files hold none.
  std::optional<float> max_samples;
};

// r's file: header from r's shape, spp, seed, method and cache_key.
std::string encode_cache_file(const Result& r);

// Fills r.visibility, r.std_error, r.stop_bound, r.penumbra,
// r.penumbra_source and, for the adaptive reference,
// r.samples from `bytes`. Returns false, leaving r as it was, for anything
// that is not exactly the file encode_cache_file() writes for `expected`
// (torn, corrupt, another version, key, method, shape or setting, values
// out of range).
bool decode_cache_file(const std::string& bytes, const CacheFileExpectation& expected, Result& r);

// The whole file at `path`; false when it cannot be read.
bool read_cache_file(const std::filesystem::path& path, std::string& bytes);

}  // namespace sb::reference::detail
