#pragma once
// The union of closed integer loops (Clipper's paths) without Clipper, in
// the common case where it is only their area sum: the exact reference's
// union (exact_rectangle.cpp), after the edges that neighbouring triangles
// share have cancelled, is often one loop, a shadow's outline, or a few
// apart from each other. Its tests are exact (integer coordinates, 128-bit
// products), so it never takes a crossing for none, and so is the area it
// returns but for one rounding to double (Clipper's ClipperLib::Area sums
// the corners' products in double, each rounded).
#include <clipper.hpp>
#include <cstddef>
#include <optional>

namespace sb::reference::detail {

// The area of the union (non-zero winding) of the first `count` of
// `loops`, each of at least three corners, when each is simple and no two
// touch: then a single loop's union is its |area| whichever way it winds,
// and counter-clockwise loops none of which lies inside another have the
// sum of their areas. Otherwise nullopt (a general clipper must decide).
std::optional<double> separate_loops_area(const ClipperLib::Paths& loops, size_t count);

}  // namespace sb::reference::detail
