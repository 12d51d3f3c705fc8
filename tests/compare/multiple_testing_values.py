#!/usr/bin/python3
"""Prints the Holm and Benjamini-Hochberg adjusted p-values that
test_multiple_testing.cpp pastes as constants. statsmodels is not at hand,
so this oracle runs each procedure as its paper states it (a rejection rule
at a given alpha) and takes as a hypothesis' adjusted p-value the smallest
alpha at which the procedure rejects it: a different route from the closed
forms harness/results/multiple_testing.cpp uses.
    /usr/bin/python3 tests/compare/multiple_testing_values.py
"""
from fractions import Fraction


def holm_rejects(p, alpha):
    """Holm (1979): test the sorted p-values in turn; reject p(k) while
    p(k) <= alpha / (m - k + 1), and stop at the first that is not."""
    m = len(p)
    order = sorted(range(m), key=lambda i: p[i])
    out = set()
    for k, i in enumerate(order, start=1):
        if p[i] > alpha / (m - k + 1):
            break
        out.add(i)
    return out


def bh_rejects(p, alpha):
    """Benjamini-Hochberg (1995): the largest k with p(k) <= k alpha / m;
    reject the k smallest."""
    m = len(p)
    order = sorted(range(m), key=lambda i: p[i])
    last = 0
    for k, i in enumerate(order, start=1):
        if p[i] <= k * alpha / m:
            last = k
    return set(order[:last])


def adjusted(p, rejects):
    """The smallest alpha in [0, 1] at which `rejects` rejects each hypothesis.
    Where the rejection set changes, alpha is one of (m - k + 1) p(k) (Holm)
    or m p(k) / k (BH); every such value, and 1, is tried."""
    m = len(p)
    candidates = {Fraction(1)}
    for k in range(1, m + 1):
        for q in p:
            candidates.add(min(Fraction(1), (m - k + 1) * q))
            candidates.add(min(Fraction(1), m * q / k))
    out = [Fraction(1)] * m
    for a in sorted(candidates, reverse=True):
        for i in rejects(p, a):
            out[i] = min(out[i], a)
    return out


cases = {
    # Benjamini & Hochberg (1995), section 4.1: the 15 p-values of a trial;
    # at 0.05 the paper's procedure rejects 4, Holm's (as Bonferroni's) 3.
    "bh1995": ["0.0001", "0.0004", "0.0019", "0.0095", "0.0201", "0.0278", "0.0298", "0.0344",
               "0.0459", "0.3240", "0.4262", "0.5719", "0.6528", "0.7590", "1.000"],
    "unsorted_ties": ["0.04", "0.01", "0.03", "0.04", "0.2", "0.001"],
    "zeros_and_ones": ["0.5", "0", "1", "0.002", "0.3", "0.002"],
    "one_of_fifty": ["0.019"] + ["1"] * 49,
}
for name, text in cases.items():
    p = [Fraction(t) for t in text]
    for label, rule in (("holm", holm_rejects), ("bh", bh_rejects)):
        adj = adjusted(p, rule)
        print(name, label, "rejected at 0.05:", len(rule(p, Fraction(5, 100))),
              "adjusted =", ", ".join(repr(float(a)) for a in adj))
