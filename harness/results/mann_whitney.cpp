#include "results/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace sb::results {
namespace {

// Coefficients c[k] of the Gaussian binomial [m+n choose m]_q: c[k] is the
// number of orderings of m x's and n y's in which the x's beat k pairs, so
// the null distribution of U is c[k] / C(m+n, m). Built as the product over
// i = 1..m of (1 - q^(n+i)) / (1 - q^i); after every step the polynomial is
// [n+i choose i]_q, whose coefficients are non-negative, so doubles stay exact
// for every sample size the harness sees (and accurate well beyond).
std::vector<double> u_counts(size_t m, size_t n) {
  if (m > n) std::swap(m, n);
  std::vector<double> c(m * n + 1, 0.0);
  c[0] = 1;
  size_t degree = 0;
  for (size_t i = 1; i <= m; ++i) {
    const size_t a = n + i;  // multiply by (1 - q^a)
    degree += n;             // the new degree: i·n
    for (size_t k = degree; k >= a; --k) {
      c[k] -= c[k - a];
      if (k == a) break;
    }
    for (size_t k = i; k <= degree; ++k) c[k] += c[k - i];  // divide by (1 - q^i)
  }
  return c;
}

double normal_sf(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

}  // namespace

MannWhitneyResult mann_whitney_u(std::span<const double> x, std::span<const double> y,
                                 MwuMethod method) {
  if (x.empty() || y.empty()) throw std::invalid_argument("mann_whitney_u: empty sample");
  const size_t n1 = x.size(), n2 = y.size(), n = n1 + n2;
  std::vector<std::pair<double, size_t>> all;  // value, 0 for x and 1 for y
  all.reserve(n);
  for (double v : x) all.emplace_back(v, 0);
  for (double v : y) all.emplace_back(v, 1);
  for (const auto& [v, s] : all)
    if (std::isnan(v)) throw std::invalid_argument("mann_whitney_u: NaN in a sample");
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  // Mid-ranks (1-based), the rank sum of x, and the tie term Σ(t³ - t).
  double r1 = 0, tie_term = 0;
  bool ties = false;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && all[j].first == all[i].first) ++j;
    const double t = double(j - i);
    const double rank = (double(i + 1) + double(j)) / 2;
    for (size_t k = i; k < j; ++k)
      if (all[k].second == 0) r1 += rank;
    if (j - i > 1) {
      ties = true;
      tie_term += t * t * t - t;
    }
    i = j;
  }
  MannWhitneyResult r;
  const double mn = double(n1) * double(n2);
  r.u1 = r1 - double(n1) * double(n1 + 1) / 2;
  const double u = std::max(r.u1, mn - r.u1);

  if (method == MwuMethod::kAuto)
    method = (n1 > 8 && n2 > 8) || ties ? MwuMethod::kAsymptotic : MwuMethod::kExact;
  r.exact = method == MwuMethod::kExact;
  double p = 1;
  if (r.exact) {
    // P(U' >= u) = P(U' <= mn - u) by symmetry. u is an integer without
    // ties; with ties (exact forced) it is truncated first, as scipy does.
    const std::vector<double> c = u_counts(n1, n2);
    const double total = std::accumulate(c.begin(), c.end(), 0.0);
    const auto last = size_t(mn - std::floor(u));
    double below = 0;
    for (size_t k = 0; k <= last && k < c.size(); ++k) below += c[k];
    p = 2 * below / total;
  } else {
    const double nd = double(n);
    const double var = mn / 12 * ((nd + 1) - tie_term / (nd * (nd - 1)));
    if (var <= 0) {
      p = 1;  // every value equal: no evidence either way
    } else {
      const double z = (u - mn / 2 - 0.5) / std::sqrt(var);
      p = 2 * normal_sf(z);
    }
  }
  r.p = std::clamp(p, 0.0, 1.0);
  return r;
}

}  // namespace sb::results
