#include "history/stored_text.h"

namespace sb::history {

namespace {

// The length in bytes of the UTF-8 character at s[i], 0 when it is not one.
std::size_t character_at(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  std::size_t n = 0;
  char32_t c = 0;
  if (b < 0x80) return 1;
  if (b >= 0xc2 && b <= 0xdf)
    n = 2, c = b & 0x1f;
  else if (b >= 0xe0 && b <= 0xef)
    n = 3, c = b & 0x0f;
  else if (b >= 0xf0 && b <= 0xf4)
    n = 4, c = b & 0x07;
  else
    return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
    c = (c << 6) | (byte(i + k) & 0x3f);
  }
  if ((n == 3 && c < 0x800) || (n == 4 && c < 0x10000) || c > 0x10ffff ||
      (c >= 0xd800 && c <= 0xdfff))
    return 0;
  return n;
}

// A C0 control, DEL, or a C1 control (U+0080 to U+009F, bytes c2 80 to c2 9f).
bool control_at(std::string_view s, std::size_t i, std::size_t length) {
  const auto b = static_cast<unsigned char>(s[i]);
  if (length == 1) return b < 0x20 || b == 0x7f;
  return length == 2 && b == 0xc2 && static_cast<unsigned char>(s[i + 1]) < 0xa0;
}

}  // namespace

std::size_t utf8_characters(std::string_view s) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < s.size(); ++count) {
    const std::size_t n = character_at(s, i);
    if (n == 0) return std::string_view::npos;
    i += n;
  }
  return count;
}

std::string utf8_prefix(std::string_view s, std::size_t characters) {
  std::size_t i = 0;
  for (std::size_t count = 0; count < characters && i < s.size(); ++count) {
    const std::size_t n = character_at(s, i);
    if (n == 0) break;
    i += n;
  }
  return std::string(s.substr(0, i));
}

std::string utf8_cut(std::string_view s, std::size_t bytes) {
  std::size_t i = 0;
  while (i < s.size()) {
    const std::size_t n = character_at(s, i);
    if (n == 0 || i + n > bytes) break;
    i += n;
  }
  return std::string(s.substr(0, i));
}

std::string quoted_excerpt(std::string_view s) {
  constexpr std::size_t kShown = 40;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "\"";
  std::size_t i = 0;
  for (std::size_t count = 0; count < kShown && i < s.size(); ++count) {
    const std::size_t n = character_at(s, i);
    if (n == 0 || control_at(s, i, n)) {
      for (std::size_t k = 0; k < (n == 0 ? 1 : n); ++k) {
        const auto b = static_cast<unsigned char>(s[i + k]);
        out += "\\x";
        out += kHex[b >> 4];
        out += kHex[b & 15];
      }
      i += n == 0 ? 1 : n;
    } else {
      out.append(s.substr(i, n));
      i += n;
    }
  }
  out += '"';
  if (i < s.size()) out += " (cut; " + std::to_string(s.size()) + " bytes in all)";
  return out;
}

std::string commit_problem(std::string_view commit) {
  if (commit.empty()) return "is empty";
  if (commit.size() > 4 * kMaxCommitCharacters || utf8_characters(commit) == std::string_view::npos)
    return commit.size() > 4 * kMaxCommitCharacters
               ? "is " + std::to_string(commit.size()) + " bytes long; a commit is at most " +
                     std::to_string(kMaxCommitCharacters) + " characters"
               : "is not UTF-8 text";
  if (utf8_characters(commit) > kMaxCommitCharacters)
    return "is " + std::to_string(utf8_characters(commit)) +
           " characters long; a commit is at most " + std::to_string(kMaxCommitCharacters);
  for (std::size_t i = 0; i < commit.size();) {
    const std::size_t n = character_at(commit, i);
    if (control_at(commit, i, n))
      return "holds a control character (at byte " + std::to_string(i) +
             "); a commit is printable text";
    i += n;
  }
  return "";
}

std::string text_problem(std::string_view text) {
  if (text.size() > kMaxStoredTextBytes)
    return "is " + std::to_string(text.size()) + " bytes long; a history's text is at most " +
           std::to_string(kMaxStoredTextBytes);
  if (utf8_characters(text) == std::string_view::npos) return "is not UTF-8 text";
  return "";
}

}  // namespace sb::history
