#pragma once
// The Pareto front of (time, error) points, both minimised: the technique
// variants for which nothing else is both at least as fast and at least as
// accurate, and strictly better in one of the two.
//
// Deliberate choices:
//  - Points with a NaN or ±inf coordinate are excluded (never on the front).
//  - Exact duplicates (equal time and equal error) do not dominate each
//    other: if one is on the front, all of them are, each with its label.
//  - Among points of equal time only the lowest error can be on the front
//    (and all points sharing that lowest error); likewise among points of
//    equal error only the fastest.
//  - The front is sorted by time, then error, then label, then input order,
//    so it is stable whatever order the points came in. Along it, time rises
//    and error falls (strictly between distinct points).
#include <cstddef>
#include <string>
#include <vector>

namespace sb::results {

struct ParetoPoint {
  double time = 0.0;
  double error = 0.0;
  std::string label;
};

// Indices into `points` of the front, in front order (see above).
std::vector<std::size_t> pareto_front_indices(const std::vector<ParetoPoint>& points);
// The front's points themselves, in the same order.
std::vector<ParetoPoint> pareto_front(const std::vector<ParetoPoint>& points);

}  // namespace sb::results
