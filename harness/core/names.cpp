#include "core/names.h"

#include <cctype>

#include "core/hash.h"

namespace sb::core {
namespace {

constexpr size_t kReadableMax = 96;
constexpr size_t kPrefixMax = 64;

bool plain_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' ||
         c == '=' || c == ',' || c == '/';
}

// True when the readable mapping below is one-to-one for `name`.
bool readable(const std::string& name) {
  if (name.empty() || name.size() > kReadableMax || name[0] == '.') return false;
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (!plain_char(c)) return false;
    if (i + 1 < name.size()) {
      const char d = name[i + 1];
      if ((c == '-' || c == '_') && d == c) return false;  // "--" is a '/', "__" a separator
      if ((c == '-' && d == '/') || (c == '/' && d == '-')) return false;
    }
  }
  return true;
}

}  // namespace

std::string file_safe(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c == '/')
      out += "--";  // no '@' or '#': oiiotool and idiff read those as frame wildcards
    else if (c == ',')
      out += '+';
    else
      out += plain_char(c) ? c : '-';
  }
  if (readable(name)) return out;
  if (out.size() > kPrefixMax) out.resize(kPrefixMax);
  while (!out.empty() && out[0] == '.') out[0] = '-';  // no hidden files, no ".."
  // FNV-1a's last bytes barely spread ("α" and "β" differ in one digit):
  // a splitmix64 finaliser makes every input byte move every output digit.
  uint64_t z = Hasher().add(name).value();
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return out + "~" + to_hex(z).substr(0, 12);
}

std::string job_id(const std::string& scene_variant, const std::string& resolution,
                   const std::string& technique_variant) {
  return file_safe(scene_variant) + "__" + file_safe(resolution) + "__" +
         file_safe(technique_variant);
}

}  // namespace sb::core
