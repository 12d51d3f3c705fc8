#pragma once
// Text quoted from input into a message: a parser's error or warning, a JSON
// excerpt, a scene's node, mesh or material name, a label, a failed job's
// reason. One function makes such text safe to print on a terminal and to
// store in a record, whoever wrote the input:
//  - cut to at most `max_chars` characters (UTF-8 characters, never part of
//    one), then "... (N bytes in all)";
//  - control characters (C0, DEL and C1; ESC starts terminal escape
//    sequences), U+2028/U+2029 and the bidirectional overrides and isolates
//    (U+202A-202E, U+2066-2069) written as \xNN or \u{XXXX}; \n as \n, \t as \t;
//  - bytes that are not UTF-8 written as \xNN.
// So the result is valid UTF-8, one line, and at most about 10 bytes per
// character allowed (a long escape), plus the tail.
#include <cstddef>
#include <string>
#include <string_view>

namespace sb::core {

// Characters kept of a quoted name, label or excerpt in a message.
inline constexpr std::size_t kQuoteChars = 200;
// Characters kept of a whole message stored as a failed job's reason or
// printed as one line (each quoted part in it is already cut to kQuoteChars).
inline constexpr std::size_t kMessageChars = 2000;

std::string bounded_text(std::string_view text, std::size_t max_chars = kQuoteChars);

// A message as one row of a table (a failed job's reason in summary.md,
// results.csv and the HTML tables): its lines joined by " / ", blank lines
// and the blanks at either end of each line left out (a compiler's log ends
// in a newline), then bounded_text.
std::string one_line_text(std::string_view text, std::size_t max_chars = kMessageChars);

// bounded_text in single quotes: 'name'.
std::string quoted_text(std::string_view text, std::size_t max_chars = kQuoteChars);

}  // namespace sb::core
