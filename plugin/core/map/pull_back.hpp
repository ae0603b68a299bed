// The pull-back of a point of a curved image: the reference point xi with X(xi) = y, by Newton's method.
#pragma once
#include <array>
#include <vector>

#include "map/element_map.hpp"

namespace dlmfsi {

// Newton's iteration xi <- xi + (dX/dxi)^-1 (y - X(xi)) from xi, stopping at |dxi| < max(1e-12,
// xi_round_off) or where the steps stall at the round-off floor (below max(1e-9, 64 xi_round_off) and no
// longer halving). xi_round_off: the size in xi of the round-off of y (a point y is known to about
// eps |y|). Where det dX/dxi is not positive at an iterate (a point beyond the triangle, where a map that is
// valid on it may fold), the step is halved back towards the previous iterate. value: X and dX/ds at the
// answer. Throws Error if it fails to converge in 80 iterations or det dX/dxi is not positive at the start.
Point newton_pull_back(const TriangleMap& map, double xi_round_off, Point y, Point xi, MapValue& value);

// newton_pull_back at n points of one triangle: y the points, xi their starting points in and the answers
// out, jacobian[q] = dX/ds at answer q as (jac[0][0], jac[0][1], jac[1][0], jac[1][1]). For a fitted map
// the first two iterations run for all points at once (evaluate_polynomial_points); a point that has not
// converged by then, or meets a determinant that is not positive, is redone by newton_pull_back from its
// start: every answer is newton_pull_back's, bit for bit. scratch: the caller's, kept across calls.
void newton_pull_back_points(const TriangleMap& map, double xi_round_off, int n, const Point* y, Point* xi,
                             std::array<double, 4>* jacobian, std::vector<double>& scratch);

}  // namespace dlmfsi
