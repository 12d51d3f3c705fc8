#include "results/multiple_testing.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace sb::results {

std::optional<Correction> parse_correction(const std::string& name) {
  if (name == "holm") return Correction::kHolm;
  if (name == "bh") return Correction::kBenjaminiHochberg;
  if (name == "none") return Correction::kNone;
  return std::nullopt;
}

const char* to_string(Correction c) {
  switch (c) {
    case Correction::kHolm:
      return "holm";
    case Correction::kBenjaminiHochberg:
      return "bh";
    case Correction::kNone:
      break;
  }
  return "none";
}

const char* correction_name(Correction c) {
  switch (c) {
    case Correction::kHolm:
      return "Holm";
    case Correction::kBenjaminiHochberg:
      return "Benjamini-Hochberg";
    case Correction::kNone:
      break;
  }
  return "no";
}

std::vector<double> adjust_p_values(std::span<const double> p, Correction c) {
  for (const double v : p)
    if (!(v >= 0 && v <= 1)) throw std::invalid_argument("adjust_p_values: p outside [0, 1]");
  std::vector<double> out(p.begin(), p.end());
  const size_t m = p.size();
  if (c == Correction::kNone || m == 0) return out;
  // order[k]: the index of the (k+1)-th smallest p; ties keep input order
  // (the adjusted values of tied p come out equal either way).
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  const double md = double(m);
  if (c == Correction::kHolm) {
    double running = 0;  // the max so far keeps the adjusted values monotone
    for (size_t k = 0; k < m; ++k) {
      running = std::max(running, std::min(1.0, (md - double(k)) * p[order[k]]));
      out[order[k]] = running;
    }
  } else {
    double running = 1;  // the min from the top down keeps them monotone
    for (size_t k = m; k-- > 0;) {
      running = std::min(running, md * p[order[k]] / double(k + 1));
      out[order[k]] = running;
    }
  }
  return out;
}

}  // namespace sb::results
