#include "gl/glsl_pieces.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace sb::gl {

namespace {

constexpr const char* kSourceStringComment = "// source string ";

size_t lines_in(const std::string& text) {
  return size_t(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

std::string assemble_glsl(const std::vector<GlslPiece>& pieces) {
  std::string out;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const GlslPiece& p = pieces[i];
    if (i == 0 && p.source_string != 0)
      throw std::logic_error("assemble_glsl: the first piece (with #version) must be string 0");
    if (p.source_string != 0) {
      out += kSourceStringComment + std::to_string(p.source_string) + ": " + p.name + "\n";
      out += "#line 1 " + std::to_string(p.source_string) + "\n";
    } else if (i > 0 && pieces[i - 1].source_string != 0) {
      // Back to the assembled text's own numbers: the line after this one.
      out += "#line " + std::to_string(lines_in(out) + 2) + " 0\n";
    }
    out += p.text;
    if (!p.text.empty() && p.text.back() != '\n') out += '\n';
  }
  return out;
}

std::vector<std::string> glsl_source_strings(const std::string& source) {
  std::vector<std::string> out;
  const std::string marker = std::string("\n") + kSourceStringComment;
  for (size_t at = source.find(marker); at != std::string::npos; at = source.find(marker, at + 1)) {
    const size_t begin = at + marker.size();
    std::string named = source.substr(begin, source.find('\n', begin) - begin);
    if (const size_t colon = named.find(": "); colon != std::string::npos)
      named.replace(colon, 2, " is ");
    out.push_back(std::move(named));
  }
  return out;
}

}  // namespace sb::gl
