#pragma once
// Text checks shared by the tests (one definition, so that a unity build of
// a test executable holds each once).
#include <string>

namespace sb::test {

// Whether `text` contains `part`.
inline bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace sb::test
