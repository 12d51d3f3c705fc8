#include "core/hash.h"

namespace sb::core {

Hasher& Hasher::add(const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t h = state_;
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;  // FNV-1a 64 prime
  }
  state_ = h;
  return *this;
}

Hasher& Hasher::add(std::string_view s) {
  const uint64_t n = s.size();
  add(&n, sizeof(n));
  return add(s.data(), s.size());
}

std::string Hasher::hex() const { return to_hex(state_); }

uint64_t fnv1a64(std::string_view bytes) {
  return Hasher().add(bytes.data(), bytes.size()).value();
}

std::string to_hex(uint64_t value) {
  static const char digits[] = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i) {
    s[size_t(i)] = digits[value & 0xf];
    value >>= 4;
  }
  return s;
}

}  // namespace sb::core
