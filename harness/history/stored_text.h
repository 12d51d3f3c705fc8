#pragma once
// What a history stores as text, checked the same way when `history add`
// writes it and when anything reads it back (a history file may come from
// anyone: docs/robustness.md "History files"):
//   a commit      1 to kMaxCommitCharacters characters of UTF-8, none a
//                 control character (C0, DEL, C1)
//   other text    UTF-8, at most kMaxStoredTextBytes bytes (a job's reason
//                 is cut to that by characters when added)
// and the report cuts text by characters, never inside one.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace sb::history {

inline constexpr std::size_t kMaxCommitCharacters = 100;
inline constexpr std::size_t kMaxStoredTextBytes = 64 * 1024;
// The largest run_order a history holds: 2^53 - 1, the largest integer a
// reader of steps.json in JavaScript (a double) still tells from its
// neighbours. Orders start at 1.
inline constexpr std::int64_t kMaxRunOrder = (std::int64_t{1} << 53) - 1;

// The length of `s` in characters when it is UTF-8 (shortest forms, no
// surrogates, at most U+10FFFF), or std::string_view::npos.
std::size_t utf8_characters(std::string_view s);

// The first `characters` characters of UTF-8 text `s` (all of it when
// shorter); bytes that are not UTF-8 end the prefix.
std::string utf8_prefix(std::string_view s, std::size_t characters);

// The longest prefix of UTF-8 text `s` of whole characters and at most
// `bytes` bytes.
std::string utf8_cut(std::string_view s, std::size_t bytes);

// `s` for a message: its first 40 characters, control characters and bytes
// that are not UTF-8 written as \xNN, in double quotes, with the length
// when it was cut.
std::string quoted_excerpt(std::string_view s);

// Why `commit` cannot be stored ("" when it can).
std::string commit_problem(std::string_view commit);

// Why `text` cannot be stored as a history's text ("" when it can).
std::string text_problem(std::string_view text);

}  // namespace sb::history
