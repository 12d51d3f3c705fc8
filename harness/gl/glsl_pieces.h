#pragma once
// A shader assembled from pieces (the kit's head and main around a
// technique's own GLSL) with #line directives, so that the compiler's
// messages name each piece's own lines. A piece of source-string number 0
// keeps the assembled text's line numbers (Mesa's "0:118(7): error" is line
// 118 of the assembled source, as Program writes it for a failed job); a
// piece of another number restarts at its line 1 ("1:12(3): error" is line
// 12 of that piece, as its author wrote it). GLSL 4.50's `#line N S` sets
// the number of the NEXT line and the source-string number.
#include <string>
#include <utility>
#include <vector>

namespace sb::gl {

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

}  // namespace sb::gl
