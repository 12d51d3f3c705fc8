// The Mann–Whitney U test against scipy.stats.mannwhitneyu (two-sided).
// Every expected value below was produced with Debian 12's python3-scipy
// 1.10.1 by tests/compare/scipy_mwu_values.py (same names, same data):
//   /usr/bin/python3 tests/compare/scipy_mwu_values.py
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "results/mann_whitney.h"

namespace {

using sb::results::mann_whitney_u;
using sb::results::MwuMethod;
using V = std::vector<double>;

struct Case {
  const char* name;
  V x, y;
  sb::results::MwuMethod method;
  bool exact;  // the method scipy's "auto" picks (or the forced one)
  double u1;   // scipy's statistic
  double p;    // scipy's pvalue
};

V arithmetic(double first, int n) {
  V v;
  for (int i = 0; i < n; ++i) v.push_back(first + i);
  return v;
}

// Samples used by more than one case.
const V kDocX{19, 22, 16, 29, 24}, kDocY{20, 11, 17, 12};
const V kSmallX{1.1, 2.3, 3.5, 4.0, 5.2}, kSmallY{2.9, 6.1, 7.4, 8.8, 9.0, 10.5};
const V kTiesX{1, 2, 2, 3, 3, 3, 4, 5, 5}, kTiesY{2, 3, 4, 4, 5, 5, 6, 6, 7, 7};

const Case kCases[] = {
    {"docstring",
     {19, 22, 16, 29, 24},
     {20, 11, 17, 12},
     sb::results::MwuMethod::kAuto,
     true,
     17.0,
     0.1111111111111111},
    {"small_exact", kSmallX, kSmallY, sb::results::MwuMethod::kAuto, true, 3.0,
     0.030303030303030304},
    {"exact_3_vs_20",
     {5.5, 12.5, 17.5},
     arithmetic(1, 20),
     sb::results::MwuMethod::kAuto,
     true,
     34.0,
     0.7634105025409372},
    {"exact_forced_10_12",
     {0.5, 3.5, 6.5, 9.5, 12.5, 15.5, 18.5, 21.5, 1.5, 4.5},
     {0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 1.0, 6.0, 11.0, 16.0, 21.0, 26.0},
     sb::results::MwuMethod::kExact,
     true,
     46.0,
     0.3809719692072634},
    {"asymptotic_15",
     {10.0, 10.7, 11.4, 10.6, 11.3, 10.5, 11.2, 10.4, 11.1, 10.3, 11.0, 10.2, 10.9, 10.1, 10.8},
     {10.450000000000001, 11.55, 11.15, 10.750000000000002, 11.850000000000001, 11.450000000000001,
      11.05, 10.65, 11.750000000000002, 11.350000000000001, 10.950000000000001, 10.55,
      11.650000000000002, 11.250000000000002, 10.850000000000001},
     sb::results::MwuMethod::kAuto,
     false,
     55.0,
     0.01806662299891238},
    {"ties", kTiesX, kTiesY, sb::results::MwuMethod::kAuto, false, 18.5, 0.031445621614229195},
    {"ties_small",
     {1, 2, 2, 3},
     {2, 3, 4, 5, 5},
     sb::results::MwuMethod::kAuto,
     false,
     2.5,
     0.07854585095119067},
    {"all_equal", V(6, 4.0), V(9, 4.0), sb::results::MwuMethod::kAuto, false, 27.0, 1.0},
    {"separated_15", arithmetic(0, 15), arithmetic(100, 15), sb::results::MwuMethod::kAuto, false,
     0.0, 3.3918213908250945e-06},
    {"small_exact_asymptotic", kSmallX, kSmallY, sb::results::MwuMethod::kAsymptotic, false, 3.0,
     0.03576376659097789},
    {"docstring_asymptotic",
     {19, 22, 16, 29, 24},
     {20, 11, 17, 12},
     sb::results::MwuMethod::kAsymptotic,
     false,
     17.0,
     0.11134688653314041},
    {"ties_exact_forced", kTiesX, kTiesY, sb::results::MwuMethod::kExact, true, 18.5,
     0.034986685141483904},
};

TEST(MannWhitney, MatchesScipy) {
  for (const auto& c : kCases) {
    const auto r = sb::results::mann_whitney_u(c.x, c.y, c.method);
    EXPECT_EQ(r.exact, c.exact) << c.name;
    EXPECT_DOUBLE_EQ(r.u1, c.u1) << c.name;
    EXPECT_NEAR(r.p, c.p, 1e-12 + 1e-9 * c.p) << c.name;
  }
}

TEST(MannWhitney, SymmetricInItsSamples) {
  for (const auto& c : kCases) {
    const auto a = sb::results::mann_whitney_u(c.x, c.y, c.method);
    const auto b = sb::results::mann_whitney_u(c.y, c.x, c.method);
    EXPECT_NEAR(a.p, b.p, 1e-12) << c.name;
    EXPECT_DOUBLE_EQ(a.u1 + b.u1, double(c.x.size() * c.y.size())) << c.name;
  }
}

// The exact null distribution sums to one: the p-value of the most central U
// is 1 (clipped), and of the most extreme one 2 / C(n1 + n2, n1).
TEST(MannWhitney, ExactTails) {
  const auto extreme =
      sb::results::mann_whitney_u(V{1, 2, 3, 4}, V{5, 6, 7, 8}, sb::results::MwuMethod::kExact);
  EXPECT_NEAR(extreme.p, 2.0 / 70.0, 1e-15);
  const auto central =
      sb::results::mann_whitney_u(V{1, 4, 5, 8}, V{2, 3, 6, 7}, sb::results::MwuMethod::kExact);
  EXPECT_DOUBLE_EQ(central.p, 1.0);
  // Large exact tables stay finite and in range.
  V a, b;
  for (int i = 0; i < 60; ++i) {
    a.push_back(2.0 * i);
    b.push_back(2.0 * i + 1.0 + (i % 3 == 0 ? 10.0 : 0.0));
  }
  const auto big = sb::results::mann_whitney_u(a, b, sb::results::MwuMethod::kExact);
  const auto approx = sb::results::mann_whitney_u(a, b, sb::results::MwuMethod::kAsymptotic);
  EXPECT_GT(big.p, 0.0);
  EXPECT_LE(big.p, 1.0);
  EXPECT_NEAR(big.p, approx.p, 0.01);
}

TEST(MannWhitney, RejectsEmptyAndNaN) {
  EXPECT_THROW(sb::results::mann_whitney_u(V{}, V{1}), std::invalid_argument);
  EXPECT_THROW(sb::results::mann_whitney_u(V{1, std::nan("")}, V{1}), std::invalid_argument);
}

}  // namespace
