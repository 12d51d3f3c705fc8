// Shaders assembled from pieces with #line directives: a piece of its own
// source-string number restarts at line 1, and the assembled text's own
// pieces keep their physical line numbers.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "gl/glsl_pieces.h"

namespace sb::gl {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(GlslPieces, APieceOfItsOwnNumberStartsAtLineOneAndTheRestKeepTheirPhysicalLines) {
  const std::string source =
      assemble_glsl({{"#version 450 core\nfloat a;\n"},
                     {"\nfloat lit_fraction(vec3 t) { return 1.0; }", 1, "lit_fraction"},
                     {"void main() {}\n"}});
  const auto lines = lines_of(source);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "#version 450 core");
  size_t own = 0, main = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i] == "#line 100001 1") own = i;
    if (lines[i] == "void main() {}") main = i;
  }
  ASSERT_GT(own, 0u) << source;
  // The piece's first line (empty) follows its directive: its line 1.
  EXPECT_EQ(lines[own + 1], "");
  EXPECT_EQ(lines[own + 2], "float lit_fraction(vec3 t) { return 1.0; }");
  // main's physical line number (1-based) is the one its directive sets.
  ASSERT_GT(main, own);
  EXPECT_EQ(lines[main - 1], "#line " + std::to_string(main + 1) + " 0") << source;
  EXPECT_EQ(glsl_source_strings(source), std::vector<std::string>{"1 is lit_fraction"});
}

TEST(GlslPieces, ALogNamesAPiecesLineWhicheverSourceStringTheCompilerPrinted) {
  // Mesa's syntax errors keep the piece's source string, its semantic
  // errors print 0: both are line 10 of piece 1.
  EXPECT_EQ(glsl_log_in_pieces("1:100004(15): error: syntax error\n"
                               "0:100010(18): error: no function with name 'f'\n"),
            "1:4(15): error: syntax error\n1:10(18): error: no function with name 'f'\n");
  // The assembled text's own lines, and numbers no piece has, stay.
  EXPECT_EQ(glsl_log_in_pieces("0:57(3): error: x at 2:3(4)"), "0:57(3): error: x at 2:3(4)");
  EXPECT_EQ(glsl_log_in_pieces("0:99999999999999999999(1): e"), "0:99999999999999999999(1): e");
}

TEST(GlslPieces, ASourceWithoutPiecesNamesNoStrings) {
  EXPECT_TRUE(glsl_source_strings("#version 450 core\nvoid main() {}\n").empty());
  EXPECT_THROW(assemble_glsl({{"x", 1, "first"}}), std::logic_error);
}

}  // namespace
}  // namespace sb::gl
