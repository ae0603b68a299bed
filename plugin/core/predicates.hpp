// Exact geometric predicates.
#pragma once
#include "point.hpp"

namespace dlmfsi {

// Sign of det [b-a, c-a]: +1 if (a, b, c) turn counter-clockwise, -1 clockwise, 0 exactly collinear.
// Exact for all finite inputs whose pairwise products neither overflow nor underflow
// (|coordinates| between about 1e-146 and 1e146): a floating-point filter decides the common case, and
// near-degenerate cases (coincident points, a point on a line, collinear edges) are decided by an
// exact expansion of ax*by - ay*bx + bx*cy - by*cx + cx*ay - cy*ax.
int orient2d(Point a, Point b, Point c);

// The same determinant evaluated exactly, without the floating-point filter (for tests).
int orient2d_exact(Point a, Point b, Point c);

}  // namespace dlmfsi
