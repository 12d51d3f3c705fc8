// core::bounded_text, the one function through which text quoted from input
// reaches a terminal or a record: cut by
// characters, never inside one; control characters, terminal escapes and
// bidirectional overrides escaped; bytes that are not UTF-8 escaped; the
// result valid UTF-8 on one line.
#include <gtest/gtest.h>

#include <string>

#include "../common/text.h"
#include "core/bounded_text.h"

namespace sb::core {
namespace {

using test::valid_utf8;

TEST(BoundedText, ShortPrintableTextIsUnchanged) {
  EXPECT_EQ(bounded_text("mesh \"Cube.001\" é 日本 😀"), "mesh \"Cube.001\" é 日本 😀");
  EXPECT_EQ(quoted_text("a"), "'a'");
}

TEST(BoundedText, CutsByCharactersNeverInsideOne) {
  std::string s;
  for (int i = 0; i < 100; ++i) s += "é日😀";  // 2, 3 and 4 bytes
  for (size_t n : {size_t(1), size_t(2), size_t(3), size_t(77), size_t(200)}) {
    const std::string b = bounded_text(s, n);
    EXPECT_TRUE(valid_utf8(b)) << n;
    const std::string kept = b.substr(0, b.find("... ("));
    // n characters of the cycle é日😀, whole.
    std::string expect;
    const char* cycle[] = {"é", "日", "😀"};
    for (size_t i = 0; i < n; ++i) expect += cycle[i % 3];
    EXPECT_EQ(kept, expect) << n;
    EXPECT_NE(b.find("(900 bytes in all)"), std::string::npos) << b;
  }
  EXPECT_EQ(bounded_text(std::string(300, 'x'), 300), std::string(300, 'x'));
}

TEST(BoundedText, EscapesControlsTerminalSequencesAndBidiOverrides) {
  // ESC ] 0 ; title BEL sets a terminal's title; ESC [ 2 J clears it.
  const std::string b = bounded_text(
      "a\x1b]0;pwned\x07"
      "b\x1b[2J\r\n\t\x7f\xc2\x9b|\u202e|\u2028");
  EXPECT_EQ(b, "a\\x1B]0;pwned\\x07b\\x1B[2J\\x0D\\n\\t\\x7F\\u{009B}|\\u{202E}|\\u{2028}");
  for (char c : b) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << b;
}

TEST(BoundedText, BytesThatAreNotUtf8AreEscaped) {
  // A stray continuation byte, a truncated sequence, an overlong '/', a
  // surrogate, beyond U+10FFFF.
  const std::string b = bounded_text("x\x80y\xe6\x97z\xc0\xafw\xed\xa0\x80v\xf4\x90\x80\x80");
  EXPECT_TRUE(valid_utf8(b)) << b;
  EXPECT_EQ(b, "x\\x80y\\xE6\\x97z\\xC0\\xAFw\\xED\\xA0\\x80v\\xF4\\x90\\x80\\x80");
}

TEST(BoundedText, AFiftyMegabyteInputCostsOnlyWhatIsKept) {
  const std::string big(50u << 20, '@');
  const std::string b = bounded_text(big);
  EXPECT_EQ(b, std::string(kQuoteChars, '@') + "... (52428800 bytes in all)");
}

TEST(BoundedText, OneLineTextJoinsLinesForATableRow) {
  // A compiler's log: a line break at its end, blank lines, indentation.
  EXPECT_EQ(one_line_text("0:3(2): error: x\n"), "0:3(2): error: x");
  EXPECT_EQ(one_line_text("first\r\n\n   second  \n\tthird\n\n"), "first / second / third");
  EXPECT_EQ(one_line_text("one"), "one");
  EXPECT_EQ(one_line_text("\n \n"), "");
  // Then bounded as any message: cut, and other controls escaped.
  EXPECT_EQ(one_line_text("ab\ncd", 4), "ab /... (7 bytes in all)");
  EXPECT_EQ(one_line_text("a\x1b[2Jb"), "a\\x1B[2Jb");
}

}  // namespace
}  // namespace sb::core
