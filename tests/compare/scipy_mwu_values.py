#!/usr/bin/python3
"""Prints the scipy.stats.mannwhitneyu values that test_mann_whitney.cpp
pastes as constants (produced with Debian 12's python3-scipy 1.10.1):
    /usr/bin/python3 tests/compare/scipy_mwu_values.py
"""
from scipy.stats import mannwhitneyu
import scipy

print("scipy", scipy.__version__)
cases = {
    "docstring": ([19, 22, 16, 29, 24], [20, 11, 17, 12], "auto"),
    "small_exact": ([1.1, 2.3, 3.5, 4.0, 5.2], [2.9, 6.1, 7.4, 8.8, 9.0, 10.5], "auto"),
    "exact_3_vs_20": ([5.5, 12.5, 17.5], [float(i) for i in range(1, 21)], "auto"),
    "exact_forced_10_12": ([float(3 * i % 23) + 0.5 for i in range(10)],
                           [float(5 * i % 29) for i in range(12)], "exact"),
    "asymptotic_15": ([10 + (7 * i % 15) * 0.1 for i in range(15)],
                      [10.4 + (11 * i % 15) * 0.1 + 0.05 for i in range(15)], "auto"),
    "ties": ([1, 2, 2, 3, 3, 3, 4, 5, 5], [2, 3, 4, 4, 5, 5, 6, 6, 7, 7], "auto"),
    "ties_small": ([1, 2, 2, 3], [2, 3, 4, 5, 5], "auto"),
    "all_equal": ([4.0] * 6, [4.0] * 9, "auto"),
    "separated_15": ([float(i) for i in range(15)], [100.0 + i for i in range(15)], "auto"),
    "small_exact_asymptotic": ([1.1, 2.3, 3.5, 4.0, 5.2], [2.9, 6.1, 7.4, 8.8, 9.0, 10.5],
                               "asymptotic"),
    "docstring_asymptotic": ([19, 22, 16, 29, 24], [20, 11, 17, 12], "asymptotic"),
    "ties_exact_forced": ([1, 2, 2, 3, 3, 3, 4, 5, 5], [2, 3, 4, 4, 5, 5, 6, 6, 7, 7], "exact"),
}
for name, (x, y, method) in cases.items():
    r = mannwhitneyu(x, y, alternative="two-sided", method=method)
    print(name, method, "x =", x, "y =", y, "U1 =", repr(float(r.statistic)),
          "p =", repr(float(r.pvalue)))
