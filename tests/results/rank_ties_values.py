#!/usr/bin/python3
"""Prints the ranking with ties that test_rank_ties.cpp pastes as constants
(Debian 12's python3-scipy 1.10.1):
    /usr/bin/python3 tests/results/rank_ties_values.py
Six variants, 30 per-frame ratios each, made by the formula the test uses;
ranked by numpy's median; each adjacent pair tested with
scipy.stats.mannwhitneyu (two-sided); Holm (1979) applied as its paper
states it, a rejection rule at alpha 0.05 (no closed form): a pair not
rejected is a tie.
"""
import numpy as np
from scipy.stats import mannwhitneyu

ALPHA = 0.05
BASES = [1.46, 1.17, 2.63, 1.29, 1.47, 1.19]  # in the group's (input) order
MULTS = [3, 5, 7, 11, 13, 17]


def samples(base, a, n=30):
    return [base * (1 + 0.1 * (((i * a) % 31) / 30.0 - 0.5)) for i in range(n)]


def holm_rejects(p, alpha):
    m = len(p)
    order = sorted(range(m), key=lambda i: p[i])
    out = set()
    for k, i in enumerate(order, start=1):
        if p[i] > alpha / (m - k + 1):
            break
        out.add(i)
    return out


s = [samples(b, a) for b, a in zip(BASES, MULTS)]
order = sorted(range(len(s)), key=lambda k: np.median(s[k]))
p = [mannwhitneyu(s[a], s[b], alternative="two-sided").pvalue for a, b in zip(order, order[1:])]
rejected = holm_rejects(p, ALPHA)
print("order (input indices):", order)
print("medians:", [repr(float(np.median(s[k]))) for k in order])
print("raw p of each adjacent pair:", [repr(float(x)) for x in p])
print("tied with the one above:", [False] + [i not in rejected for i in range(len(p))])
