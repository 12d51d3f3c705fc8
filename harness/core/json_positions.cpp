#include "core/json_positions.h"

#include <algorithm>

namespace sb::core {

JsonPositions::JsonPositions(const std::string& text, size_t line_offset)
    : line_offset_(line_offset) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts_.push_back(i + 1);
}

void JsonPositions::add(std::string pointer, size_t offset) {
  offsets_.insert_or_assign(std::move(pointer), offset);
}

TextPosition JsonPositions::position_of(size_t offset) const {
  if (line_starts_.empty()) return {};
  const auto next = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const auto line = size_t(next - line_starts_.begin());  // 1-based: next is one past it
  return {line + line_offset_, offset - line_starts_[line - 1] + 1};
}

TextPosition JsonPositions::find(const std::string& pointer) const {
  std::string p = pointer == "/" ? std::string() : pointer;
  for (;;) {
    const auto it = offsets_.find(p);
    if (it != offsets_.end()) return position_of(it->second);
    if (p.empty()) return {};
    const size_t slash = p.rfind('/');
    p.erase(slash == std::string::npos ? 0
                                       : slash);  // "key" (no slash) falls back to the whole text
  }
}

InputError located(const InputError& error, const std::string& file,
                   const JsonPositions& positions) {
  if (error.position().known() || error.file() != file) return error;
  const std::string& where = error.where();
  if (!where.empty() && where[0] != '/') return error;  // not a JSON pointer
  const TextPosition at = positions.find(where);
  if (!at.known()) return error;
  return InputError(error.file(), where.empty() ? "/" : where, error.problem(), at);
}

}  // namespace sb::core
