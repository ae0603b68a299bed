// Exact geometric predicates.
#pragma once
#include <cmath>

#include "point.hpp"

namespace dlmfsi {

// Sign of det [b-a, c-a]: +1 if (a, b, c) turn counter-clockwise, -1 clockwise, 0 exactly collinear.
// Exact for all finite inputs whose pairwise products neither overflow nor underflow
// (|coordinates| between about 1e-146 and 1e146): a floating-point filter decides the common case, and
// near-degenerate cases (coincident points, a point on a line, collinear edges) are decided by an
// exact expansion of ax*by - ay*bx + bx*cy - by*cx + cx*ay - cy*ax.
inline int orient2d(Point a, Point b, Point c);

// The same determinant evaluated exactly, without the floating-point filter.
int orient2d_exact(Point a, Point b, Point c);

inline int orient2d(Point a, Point b, Point c) {
  const double left = (a.x - c.x) * (b.y - c.y);
  const double right = (a.y - c.y) * (b.x - c.x);
  const double det = left - right;
  // Shewchuk's ccwerrboundA = (3 + 16 eps) eps with eps = 2^-53.
  const double bound = 3.3306690738754716e-16 * (std::fabs(left) + std::fabs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d_exact(a, b, c);
}

}  // namespace dlmfsi
