#include "results/pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace sb::results {

std::vector<std::size_t> pareto_front_indices(const std::vector<ParetoPoint>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i].time) && std::isfinite(points[i].error)) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const ParetoPoint& p = points[a];
    const ParetoPoint& q = points[b];
    return std::tie(p.time, p.error, p.label, a) < std::tie(q.time, q.error, q.label, b);
  });

  // Sweep groups of equal time in rising time. A group's lowest error is on
  // the front iff it beats every strictly faster point's error; all points of
  // the group sharing that lowest error (duplicates) go on the front together.
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t g = 0; g < order.size();) {
    const double t = points[order[g]].time;
    const double e = points[order[g]].error;  // the group's lowest: sorted by error
    std::size_t end = g;
    while (end < order.size() && points[order[end]].time == t) ++end;
    if (e < best) {
      for (std::size_t k = g; k < end && points[order[k]].error == e; ++k)
        front.push_back(order[k]);
      best = e;
    }
    g = end;
  }
  return front;
}

std::vector<ParetoPoint> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<ParetoPoint> out;
  for (std::size_t i : pareto_front_indices(points)) out.push_back(points[i]);
  return out;
}

}  // namespace sb::results
