#include "gl/glsl_pieces.h"

#include <algorithm>
#include <cctype>
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
  // Each "N:L(" — digits, a colon, digits, an opening parenthesis — whose L
  // has at most nine digits (a longer one is no line this numbering made).
  const auto digits_from = [&](size_t i) {
    size_t j = i;
    while (j < log.size() && std::isdigit(static_cast<unsigned char>(log[j])) != 0) ++j;
    return j;
  };
  std::string out;
  size_t i = 0;
  while (i < log.size()) {
    const bool starts = std::isdigit(static_cast<unsigned char>(log[i])) != 0 &&
                        (i == 0 || std::isdigit(static_cast<unsigned char>(log[i - 1])) == 0);
    const size_t colon = starts ? digits_from(i) : i;
    const size_t line_end =
        starts && colon < log.size() && log[colon] == ':' ? digits_from(colon + 1) : colon + 1;
    if (!starts || line_end == colon + 1 || line_end >= log.size() || log[line_end] != '(' ||
        line_end - colon - 1 > 9) {
      out += log[i++];
      continue;
    }
    const long line = std::stol(log.substr(colon + 1, line_end - colon - 1));
    if (line >= kGlslLineBlock)
      out += std::to_string(line / kGlslLineBlock) + ":" + std::to_string(line % kGlslLineBlock);
    else
      out.append(log, i, line_end - i);
    i = line_end;
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
