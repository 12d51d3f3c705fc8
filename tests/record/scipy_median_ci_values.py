#!/usr/bin/python3
"""Prints the ranks of the median's 95 % interval from order statistics that
test_median_interval.cpp pastes as constants (produced with Debian 12's
python3-scipy 1.10.1):
    /usr/bin/python3 tests/record/scipy_median_ci_values.py
j is the largest rank with binom.cdf(j - 1, n, 0.5) <= 0.025 (the interval
[x_(j), x_(n+1-j)]), and the coverage 1 - 2 binom.cdf(j - 1, n, 0.5); for
n < 6 no rank qualifies and the range (j = 1) is printed with its coverage.
"""
from scipy.stats import binom
import scipy

print("scipy", scipy.__version__)
for n in [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 15, 20, 25, 30, 40, 50, 71, 100, 1000, 100000]:
    j = 0
    for k in range(1, n // 2 + 2):
        if binom.cdf(k - 1, n, 0.5) <= 0.025:
            j = k
        else:
            break
    if j == 0:
        j = 1
    print("{%d, %d, %d, %r}," % (n, j, n + 1 - j, float(1 - 2 * binom.cdf(j - 1, n, 0.5))))
