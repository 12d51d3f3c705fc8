#pragma once
// Text checks shared by the tests (one definition, so that a unity build of
// a test executable holds each once).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sb::test {

// Whether `text` contains `part`.
inline bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A file's whole content ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Writes `text` to `p`, replacing it.
inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

}  // namespace sb::test
