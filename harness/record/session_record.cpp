#include "record/session_record.h"

#include <cmath>
#include <string_view>

#include "record/fields.h"

namespace sb::record {
namespace {

bool session_id(std::string_view id) {
  if (id.size() != 16) return false;
  for (char c : id)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

// Printable ASCII, at most `max` bytes, each byte one of `allowed` or any
// printable one when `allowed` is empty.
bool plain_text(std::string_view text, size_t max, std::string_view allowed = {}) {
  if (text.size() > max) return false;
  for (char c : text) {
    if (c < 0x20 || c > 0x7e) return false;
    if (!allowed.empty() && allowed.find(c) == std::string_view::npos) return false;
  }
  return true;
}

}  // namespace

void SessionRecord::check(const SessionRecord& s, const Fields& f) {
  if (!session_id(s.id)) throw RecordError(f.pointer_of("id"), "expected 16 lowercase hex digits");
  if (!plain_text(s.started, 40, "0123456789-T:.Z+"))
    throw RecordError(f.pointer_of("started"), "expected a UTC ISO 8601 time");
  if (!plain_text(s.host, 255))
    throw RecordError(f.pointer_of("host"),
                      "expected a host name: printable ASCII, at most 255 bytes");
  if (!std::isfinite(s.load_average) || s.load_average < 0)
    throw RecordError(f.pointer_of("load_average"), "expected a finite number >= 0");
  if (s.retimed_from && *s.retimed_from != kUnrecordedSession && !session_id(*s.retimed_from))
    throw RecordError(f.pointer_of("retimed_from"),
                      "expected 16 lowercase hex digits or \"unrecorded\"");
}

}  // namespace sb::record
