#include <gtest/gtest.h>

#include "core/error.h"
#include "core/params.h"

namespace sb {

using core::bool_param;
using core::choice_param;
using core::float_param;
using core::InputError;
using core::int_param;
using core::odd;
using core::Params;
using core::ParamSpec;
using core::resolve_params;

namespace {

std::vector<ParamSpec> specs() {
  return {int_param("n", 4, 1, 10, ""), float_param("x", 0.5, 0.0, 1.0, ""),
          bool_param("b", true, ""), choice_param("c", "a", {"a", "b"}, ""),
          odd(int_param("k", 3, 1, 9, ""))};
}

TEST(Params, DefaultsAreFilledIn) {
  const Params p = resolve_params(specs(), nlohmann::json::object(), "f.json", "/p");
  EXPECT_EQ(p.get_int("n"), 4);
  EXPECT_FLOAT_EQ(p.get_float("x"), 0.5f);
  EXPECT_TRUE(p.get_bool("b"));
  EXPECT_EQ(p.get_string("c"), "a");
}

TEST(Params, IntegralFloatsAreAcceptedAsIntegers) {
  const Params p = resolve_params(specs(), {{"n", 7.0}}, "f.json", "/p");
  EXPECT_EQ(p.get_int("n"), 7);
  EXPECT_TRUE(p.json()["n"].is_number_integer());
}

TEST(Params, EachRuleIsChecked) {
  const auto fails = [](const nlohmann::json& given, const std::string& fragment) {
    try {
      resolve_params(specs(), given, "f.json", "/p");
      return std::string("no error");
    } catch (const InputError& e) {
      const std::string w = e.what();
      return w.find(fragment) == std::string::npos ? w : std::string();
    }
  };
  EXPECT_EQ(
      fails({{"n", 7.5}}, "f.json: at /p/n: parameter 'n': expected an integer, found number 7.5"),
      "");
  EXPECT_EQ(fails({{"n", 11}}, "expected an integer in [1, 10], found 11"), "");
  EXPECT_EQ(fails({{"x", -0.1}}, "at /p/x: parameter 'x': expected a number in [0, 1], found -0.1"),
            "");
  EXPECT_EQ(fails({{"b", 1}}, "expected true or false, found number 1"), "");
  EXPECT_EQ(fails({{"c", "z"}}, "expected one of \"a\", \"b\", found \"z\""), "");
  EXPECT_EQ(fails({{"k", 4}}, "expected an odd integer, found 4"), "");
  EXPECT_EQ(fails({{"q", 1}}, "at /p/q: unknown parameter 'q' (expected one of: n, x, b, c, k)"),
            "");
  EXPECT_EQ(
      fails(nlohmann::json::array(), "at /p: expected parameters (an object), found array []"), "");
}

}  // namespace
}  // namespace sb
