// The pull-back of a point of a curved image: the reference point xi with X(xi) = y, by Newton's method.
#pragma once
#include "triangle_map.hpp"

namespace dlmfsi {

// Newton's iteration xi <- xi + (dX/dxi)^-1 (y - X(xi)) from xi, stopping at |dxi| < max(1e-12,
// xi_round_off) or where the steps stall at the round-off floor (below max(1e-9, 64 xi_round_off) and no
// longer halving). xi_round_off: the size in xi of the round-off of y (a point y is known to about
// eps |y|). Where det dX/dxi is not positive at an iterate (a point beyond the triangle, where a map that is
// valid on it may fold), the step is halved back towards the previous iterate. value: X and dX/ds at the
// answer. Throws Error if it fails to converge in 80 iterations or det dX/dxi is not positive at the start.
Point newton_pull_back(const TriangleMap& map, double xi_round_off, Point y, Point xi, MapValue& value);

}  // namespace dlmfsi
