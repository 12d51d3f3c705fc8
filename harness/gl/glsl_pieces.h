#pragma once
// A shader assembled from pieces (the kit's head and main around a
// technique's own GLSL) with #line directives, so that the compiler's
// messages name each piece's own lines. A piece of source-string number 0
// keeps the assembled text's line numbers (Mesa's "0:118(7): error" is line
// 118 of the assembled source, as Program writes it for a failed job); a
// piece of another number S counts its own lines ("1:12(3): error" is line
// 12 of that piece, as its author wrote it). GLSL 4.50's `#line N S` sets
// the number of the NEXT line and the source-string number.
//
// Mesa keeps S in syntax errors but reports semantic ones (an undefined
// name, a type mismatch) with source string 0 and the piece's own line, so
// S is also written into the line: piece S's line n is numbered
// S·kGlslLineBlock + n, and glsl_log_in_pieces() turns either report back
// into "S:n".
#include <string>
#include <utility>
#include <vector>

namespace sb::gl {

// Lines per source string in the numbering above: a piece or an assembled
// shader holds fewer.
inline constexpr long kGlslLineBlock = 100000;

struct GlslPiece {
  // A piece numbered as the assembled text (source string 0).
  GlslPiece(std::string text_) : text(std::move(text_)) {}  // NOLINT(google-explicit-constructor)
  // A piece of its own number, called `name_` in messages.
  GlslPiece(std::string text_, int source_string_, std::string name_)
      : text(std::move(text_)), source_string(source_string_), name(std::move(name_)) {}
  std::string text;
  int source_string = 0;  // 0: the assembled source's own numbering
  std::string name;       // of a piece with its own number: what a message calls it
};

// The pieces in order, each on lines of its own. The first must hold the
// #version line, first, and have source-string number 0. A piece with its
// own number is preceded by a comment naming it ("// source string 1:
// lit_fraction"), which Program's compile errors quote.
std::string assemble_glsl(const std::vector<GlslPiece>& pieces);

// The pieces of their own number that assemble_glsl named in its
// comments, as "1 is lit_fraction"; empty for a source it did not assemble.
std::vector<std::string> glsl_source_strings(const std::string& source);

// A compiler log of an assembled source with each "N:L(C)" whose L is
// S·kGlslLineBlock + n written "S:n(C)", whatever N the compiler printed;
// other positions (the assembled text's own) as they are.
std::string glsl_log_in_pieces(const std::string& log);

}  // namespace sb::gl
