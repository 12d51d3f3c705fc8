// JsonPositions: a JSON pointer's value located by line and column in the
// text it came from, the expected places found in the fixture text itself.
#include <gtest/gtest.h>

#include <string>

#include "core/json_positions.h"

namespace sb {

using core::JsonPositions;
using core::TextPosition;

namespace {

// The 1-based line and column of the first `token` in `text`.
TextPosition where_in(const std::string& text, const std::string& token) {
  const size_t at = text.find(token);
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < at; ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  return {line, at - line_start + 1};
}

const std::string kText = "{\n  \"frames\": {\n    \"timed\": -3\n  },\n  \"name\": \"x\"\n}\n";

JsonPositions positions_of_text() {
  JsonPositions p(kText);
  p.add("", kText.find('{'));
  p.add("/frames", kText.find("{\n    "));
  p.add("/frames/timed", kText.find("-3"));
  p.add("/name", kText.find("\"x\""));
  return p;
}

TEST(JsonPositions, AValueIsFoundAtItsLineAndColumn) {
  const JsonPositions p = positions_of_text();
  const TextPosition timed = p.find("/frames/timed"), expected = where_in(kText, "-3");
  EXPECT_EQ(timed.line, expected.line);
  EXPECT_EQ(timed.column, expected.column);
  EXPECT_EQ(p.find("/name").line, where_in(kText, "\"x\"").line);
}

TEST(JsonPositions, AMissingMemberIsPlacedAtTheObjectItIsMissingFrom) {
  const JsonPositions p = positions_of_text();
  const TextPosition missing = p.find("/frames/warmup"), frames = p.find("/frames");
  EXPECT_EQ(missing.line, frames.line);
  EXPECT_EQ(missing.column, frames.column);
}

TEST(JsonPositions, APointerWithoutASlashFallsBackToTheWholeTextInsteadOfThrowing) {
  const JsonPositions p = positions_of_text();
  TextPosition at;
  EXPECT_NO_THROW(at = p.find("frames"));
  EXPECT_EQ(at.line, 1u);
  EXPECT_EQ(at.column, 1u);
}

TEST(JsonPositions, LinesOfAJsonLinesFileAreOffset) {
  JsonPositions p("{\"a\": 1}", 41);
  p.add("/a", 6);
  EXPECT_EQ(p.find("/a").line, 42u);
  EXPECT_EQ(p.find("/a").column, 7u);
}

}  // namespace
}  // namespace sb
