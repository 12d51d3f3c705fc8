#pragma once
// A small, stable content hash for cache keys and record fingerprints:
// 64-bit FNV-1a over the bytes fed in, in order. Not cryptographic; stable
// across runs and builds on little-endian hosts (numbers hash their bytes).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

namespace sb::core {

class Hasher {
 public:
  Hasher& add(const void* data, size_t size);
  // Strings are length-prefixed so that ("ab","c") and ("a","bc") differ.
  Hasher& add(std::string_view s);
  Hasher& add(const char* s) { return add(std::string_view(s)); }
  Hasher& add(const std::string& s) { return add(std::string_view(s)); }
  template <typename T>
  requires std::is_arithmetic_v<T> || std::is_enum_v<T> Hasher& add(T value) {
    return add(&value, sizeof(value));
  }

  uint64_t value() const { return state_; }
  std::string hex() const;  // 16 lowercase hex digits

 private:
  uint64_t state_ = 0xcbf29ce484222325ull;  // FNV-1a 64 offset basis
};

// One-shot helper: FNV-1a 64 of a byte string.
uint64_t fnv1a64(std::string_view bytes);
std::string to_hex(uint64_t value);

}  // namespace sb::core
