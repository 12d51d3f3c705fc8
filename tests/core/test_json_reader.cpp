// JsonReader: the one reader of JSON values by pointer that configs,
// technique parameters and run records share. Each check fails at the
// value's pointer with one phrasing, asserted here word for word.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/json_reader.h"

namespace sb {

using core::describe;
using core::JsonReader;

namespace {

using json = nlohmann::json;

// What a check failed with: "<pointer>: <problem>".
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const JsonReader kReader([](const std::string& pointer, const std::string& problem) {
  throw Failure(pointer + ": " + problem);
});

template <class F>
std::string failure(F&& read) {
  try {
    read();
  } catch (const Failure& f) {
    return f.what();
  }
  return "no failure";
}

TEST(JsonReader, WrongTypesAreDescribedByTypeAndText) {
  EXPECT_EQ(failure([] { kReader.string(json(3), "/a"); }),
            "/a: expected a string, found number 3");
  EXPECT_EQ(failure([] { kReader.boolean(json("yes"), "/b"); }),
            "/b: expected true or false, found string \"yes\"");
  EXPECT_EQ(failure([] { kReader.integer(json(2.5), "/c", 0, 10); }),
            "/c: expected an integer, found number 2.5");
  EXPECT_EQ(failure([] { kReader.number(json(nullptr), "/d"); }),
            "/d: expected a number, found null");
  EXPECT_EQ(failure([] { kReader.object(json::array({1}), "/e", "frame counts"); }),
            "/e: expected frame counts (an object), found array [1]");
  EXPECT_EQ(failure([] { kReader.object(json(true), ""); }),
            ": expected an object, found boolean true");
  EXPECT_EQ(failure([] { kReader.array(json::object(), "/f", "numbers"); }),
            "/f: expected an array of numbers, found object {}");
  EXPECT_EQ(failure([] { kReader.record_number(json("fast"), "/g"); }),
            "/g: expected a number (or \"nan\", \"inf\", \"-inf\"), found string \"fast\"");
}

TEST(JsonReader, ValuesOutOfRangeAreShownAsTheirText) {
  EXPECT_EQ(failure([] { kReader.integer(json(0), "/a", 1, 16384); }),
            "/a: expected an integer in [1, 16384], found 0");
  EXPECT_EQ(failure([] { kReader.number(json(0.5), "/b", 1, 604800); }),
            "/b: expected a number in [1, 604800], found 0.5");
  EXPECT_EQ(failure([] { kReader.number(json(0.2), "/c", 0, 0.1); }),
            "/c: expected a number in [0, 0.1], found 0.2");
  EXPECT_EQ(failure([] { kReader.unsigned_integer(json(-1), "/d"); }),
            "/d: expected an integer in [0, 18446744073709551615], found -1");
  EXPECT_EQ(failure([] {
              kReader.integer(json(std::uint64_t(1) << 63), "/e",
                              std::numeric_limits<std::int64_t>::min(),
                              std::numeric_limits<std::int64_t>::max());
            }),
            "/e: expected an integer in [-9223372036854775808, 9223372036854775807], found "
            "9223372036854775808");
  EXPECT_EQ(failure([] {
              kReader.choice(json("median"), "/f", {"none", "box"});
            }),
            "/f: expected one of \"none\", \"box\", found \"median\"");
  EXPECT_EQ(failure([] {
              kReader.choice(json(1), "/f", {"none", "box"});
            }),
            "/f: expected one of \"none\", \"box\", found number 1");
  EXPECT_EQ(failure([] { kReader.refuse(json(4), "/g", "an odd integer"); }),
            "/g: expected an odd integer, found 4");
}

TEST(JsonReader, AMissingKeyIsReportedAtItsObject) {
  EXPECT_EQ(failure([] {
              kReader.member(json{{"warmup", 2}}, "/frames", "timed");
            }),
            "/frames: missing required key \"timed\" in this object");
  EXPECT_EQ(kReader.member(json{{"timed", 2}}, "/frames", "timed"), json(2));
}

TEST(JsonReader, UnknownKeysAreNamedWithTheKnownOnes) {
  EXPECT_EQ(failure([] {
              kReader.only_keys(json{{"timd", 3}}, "/frames", {"warmup", "timed"});
            }),
            "/frames/timd: unknown key 'timd' (expected one of: warmup, timed); did you mean "
            "timed?");
  EXPECT_EQ(failure([] {
              kReader.only_keys(json{{"q", 1}}, "/p", {}, "parameter");
            }),
            "/p/q: unknown parameter 'q' (expected none)");
  // The key is one token of the pointer: "/" and "~" escaped.
  EXPECT_EQ(failure([] {
              kReader.only_keys(json{{"a/b~", 1}}, "", {"x"});
            }),
            "/a~1b~0: unknown key 'a/b~' (expected one of: x)");
}

TEST(JsonReader, AcceptedValuesAreReturned) {
  EXPECT_EQ(kReader.integer(json(7), "", 1, 10), 7);
  EXPECT_EQ(kReader.integer(json(7.0), "", 1, 10, true), 7);
  EXPECT_EQ(failure([] { kReader.integer(json(7.0), "/n", 1, 10); }),
            "/n: expected an integer, found number 7.0");
  EXPECT_EQ(failure([] { kReader.integer(json(11.0), "/n", 1, 10, true); }),
            "/n: expected an integer in [1, 10], found 11.0");
  EXPECT_EQ(kReader.unsigned_integer(json(std::uint64_t(-1)), ""), std::uint64_t(-1));
  EXPECT_TRUE(std::isnan(kReader.record_number(json("nan"), "")));
  EXPECT_EQ(kReader.record_number(json("-inf"), ""), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(kReader.choice(json("box"), "", {"none", "box"}), "box");
}

TEST(JsonReader, DescribeCutsLongValuesAtACharacterBoundary) {
  EXPECT_EQ(describe(json("abc")), "string \"abc\"");
  const std::string long_text(100, 'x');
  EXPECT_EQ(describe(json(long_text)),
            "string \"" + std::string(56, 'x') + "... (102 bytes in all)");
  // Cut by characters (core::bounded_text): 57 of them, "é" (two bytes) one.
  const std::string accents = std::string(55, 'x') + "\xC3\xA9\xC3\xA9\xC3\xA9";
  EXPECT_EQ(describe(json(accents)),
            "string \"" + std::string(55, 'x') + "\xC3\xA9... (63 bytes in all)");
}

}  // namespace
}  // namespace sb
