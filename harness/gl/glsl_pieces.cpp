#include "gl/glsl_pieces.h"

#include <algorithm>
#include <regex>
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
      out += "#line " + std::to_string(p.source_string * kGlslLineBlock + 1) + " " +
             std::to_string(p.source_string) + "\n";
    } else if (i > 0 && pieces[i - 1].source_string != 0) {
      // Back to the assembled text's own numbers: the line after this one.
      out += "#line " + std::to_string(lines_in(out) + 2) + " 0\n";
    }
    out += p.text;
    if (!p.text.empty() && p.text.back() != '\n') out += '\n';
  }
  return out;
}

std::string glsl_log_in_pieces(const std::string& log) {
  static const std::regex position(R"((\d+):(\d+)\((\d+)\))");
  std::string out;
  auto from = log.cbegin();
  for (std::sregex_iterator it(log.begin(), log.end(), position), end; it != end; ++it) {
    const std::smatch& m = *it;
    out.append(from, m[0].first);
    // Nine digits at most: a longer number is no line this numbering made.
    const long line = m[2].length() <= 9 ? std::stol(m[2].str()) : 0;
    if (line >= kGlslLineBlock)
      out += std::to_string(line / kGlslLineBlock) + ":" + std::to_string(line % kGlslLineBlock) +
             "(" + m[3].str() + ")";
    else
      out += m[0].str();
    from = m[0].second;
  }
  out.append(from, log.cend());
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
