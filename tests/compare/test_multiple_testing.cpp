// Holm and Benjamini-Hochberg adjusted p-values against an oracle that runs
// each procedure's rejection rule (tests/compare/multiple_testing_values.py,
// exact fractions; its values are pasted here), including the paper example
// of Benjamini & Hochberg (1995): 15 p-values, 4 rejected at 0.05 by BH and
// 3 by Holm.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "results/multiple_testing.h"

namespace {

using sb::results::adjust_p_values;
using sb::results::Correction;

void expect_adjusted(const std::vector<double>& p, sb::results::Correction c,
                     const std::vector<double>& want) {
  const std::vector<double> got = sb::results::adjust_p_values(p, c);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got[i], want[i], 1e-12 * (1 + want[i])) << sb::results::to_string(c) << " at " << i;
}

int rejected(const std::vector<double>& adjusted, double alpha) {
  int n = 0;
  for (double a : adjusted) n += a <= alpha;
  return n;
}

const std::vector<double> kBh1995 = {0.0001, 0.0004, 0.0019, 0.0095, 0.0201, 0.0278, 0.0298, 0.0344,
                                     0.0459, 0.3240, 0.4262, 0.5719, 0.6528, 0.7590, 1.000};

TEST(MultipleTesting, PaperExampleHolm) {
  expect_adjusted(kBh1995, sb::results::Correction::kHolm,
                  {0.0015, 0.0056, 0.0247, 0.114, 0.2211, 0.278, 0.278, 0.278, 0.3213, 1.0, 1.0,
                   1.0, 1.0, 1.0, 1.0});
  EXPECT_EQ(rejected(sb::results::adjust_p_values(kBh1995, sb::results::Correction::kHolm), 0.05),
            3);
}

TEST(MultipleTesting, PaperExampleBenjaminiHochberg) {
  expect_adjusted(
      kBh1995, sb::results::Correction::kBenjaminiHochberg,
      {0.0015, 0.003, 0.0095, 0.035625, 0.0603, 0.06385714285714286, 0.06385714285714286, 0.0645,
       0.0765, 0.486, 0.5811818181818181, 0.714875, 0.7532307692307693, 0.8132142857142857, 1.0});
  EXPECT_EQ(
      rejected(sb::results::adjust_p_values(kBh1995, sb::results::Correction::kBenjaminiHochberg),
               0.05),
      4);
}

TEST(MultipleTesting, UnsortedInputWithTies) {
  const std::vector<double> p = {0.04, 0.01, 0.03, 0.04, 0.2, 0.001};
  expect_adjusted(p, sb::results::Correction::kHolm, {0.12, 0.05, 0.12, 0.12, 0.2, 0.006});
  expect_adjusted(p, sb::results::Correction::kBenjaminiHochberg,
                  {0.048, 0.03, 0.048, 0.048, 0.2, 0.006});
}

TEST(MultipleTesting, ZerosAndOnes) {
  const std::vector<double> p = {0.5, 0, 1, 0.002, 0.3, 0.002};
  expect_adjusted(p, sb::results::Correction::kHolm, {1.0, 0.0, 1.0, 0.01, 0.9, 0.01});
  expect_adjusted(p, sb::results::Correction::kBenjaminiHochberg,
                  {0.6, 0.0, 1.0, 0.004, 0.45, 0.004});
}

TEST(MultipleTesting, OneSmallPAmongFifty) {
  std::vector<double> p(50, 1.0);
  p[0] = 0.019;
  std::vector<double> want(50, 1.0);
  want[0] = 0.95;
  expect_adjusted(p, sb::results::Correction::kHolm, want);
  expect_adjusted(p, sb::results::Correction::kBenjaminiHochberg, want);
}

TEST(MultipleTesting, NoneKeepsThePValues) {
  expect_adjusted(kBh1995, sb::results::Correction::kNone, kBh1995);
  EXPECT_TRUE(sb::results::adjust_p_values({}, sb::results::Correction::kHolm).empty());
  expect_adjusted({0.03}, sb::results::Correction::kHolm, {0.03});  // a family of one
}

TEST(MultipleTesting, NamesAndBadInput) {
  EXPECT_EQ(sb::results::parse_correction("holm"), sb::results::Correction::kHolm);
  EXPECT_EQ(sb::results::parse_correction("bh"), sb::results::Correction::kBenjaminiHochberg);
  EXPECT_EQ(sb::results::parse_correction("none"), sb::results::Correction::kNone);
  EXPECT_FALSE(sb::results::parse_correction("bonferroni"));
  EXPECT_THROW(
      sb::results::adjust_p_values(std::vector<double>{0.5, 1.5}, sb::results::Correction::kHolm),
      std::invalid_argument);
  EXPECT_THROW(
      sb::results::adjust_p_values(std::vector<double>{-0.1}, sb::results::Correction::kNone),
      std::invalid_argument);
}

}  // namespace
