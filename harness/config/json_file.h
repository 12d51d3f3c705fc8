#pragma once
// Reading JSON that a user (or anyone who can write a file) controls: a
// config, a results file handed to `report` or `compare`. Every way such
// input can be wrong becomes an sb::InputError naming the file and the place
// (line and column, and the JSON pointer when there is one):
//   - not a regular file (a FIFO, /dev/zero, a folder) or larger than the cap;
//   - invalid JSON, and numbers that overflow a double (1e400);
//   - nesting deeper than the cap (64: no config needs more, and deep input
//     would otherwise exhaust the stack wherever it is walked recursively);
//   - a key twice in one object (the second would silently win).
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_positions.h"

namespace sb::config {

struct JsonLimits {
  size_t max_bytes = size_t(16) << 20;
  int max_depth = 64;
};

// Parses `text`; `file` names it in messages, `line_offset` is added to line
// numbers (for one line of a JSON Lines file). With `positions`, records
// where each value starts, for messages about values found wrong later.
nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const JsonLimits& limits = {}, size_t line_offset = 0,
                               core::JsonPositions* positions = nullptr);

// Reads and parses a regular file of at most limits.max_bytes.
nlohmann::json read_json_file(const std::string& path, const JsonLimits& limits = {});

// Reads a regular file of at most max_bytes (InputError otherwise).
std::string read_input_file(const std::string& path, size_t max_bytes, const std::string& what);

}  // namespace sb::config
