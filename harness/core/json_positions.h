#pragma once
// Where each value of a JSON text starts, by JSON pointer, so that an error
// found long after parsing (a technique parameter out of range, an unknown
// scene type, a scene that cannot be built) still names the line and column
// of the value it is about, as a compiler or pbrt would. nlohmann::json keeps
// no positions: config/json_file.h records them while it parses.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"

namespace sb::core {

class JsonPositions {
 public:
  JsonPositions() = default;
  // `text` is the JSON text the byte offsets are into; `line_offset` is
  // added to every line (one line of a JSON Lines file).
  explicit JsonPositions(const std::string& text, size_t line_offset = 0);

  // The value at `pointer` (RFC 6901, escaped) starts at byte `offset`; a
  // pointer added again (a key twice) moves to the later offset.
  void add(std::string pointer, size_t offset);

  // The start of the value at `pointer`; a pointer to a member that is not
  // there (a missing key) gives its nearest enclosing value's. Unknown
  // (line 0) when nothing was recorded. "/" and "" are the whole text.
  TextPosition find(const std::string& pointer) const;

  bool empty() const { return offsets_.empty(); }

 private:
  TextPosition position_of(size_t offset) const;
  std::vector<size_t> line_starts_;  // byte offset of each line's first byte
  size_t line_offset_ = 0;
  std::map<std::string, size_t> offsets_;
};

// `error` with the position of its JSON pointer in `positions`, when it is
// about `file` and has none yet; otherwise `error` unchanged.
InputError located(const InputError& error, const std::string& file,
                   const JsonPositions& positions);

}  // namespace sb::core
