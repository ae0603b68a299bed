// Exact geometric predicates.
#pragma once
#include <algorithm>
#include <cmath>

#include "point.hpp"

namespace dlmfsi {

// Sign of det [b-a, c-a]: +1 if (a, b, c) turn counter-clockwise, -1 clockwise, 0 exactly collinear.
// Exact for all finite inputs: a floating-point filter decides the common case, and near-degenerate
// cases (coincident points, a point on a line, collinear edges) are decided by an exact expansion of
// ax*by - ay*bx + bx*cy - by*cx + cx*ay - cy*ax, or, when a product leaves the range where that
// expansion is exact (coordinates below about 1e-146 or above 1e146, subnormals), by integer arithmetic.
inline int orient2d(Point a, Point b, Point c);

// The same determinant evaluated exactly, without the floating-point filter.
int orient2d_exact(Point a, Point b, Point c);

// Sign of the cross product (q - p) x (s - r) of two edge directions: +1 if s - r points to the left of
// q - p, exact for all finite inputs (the same filter, then an exact evaluation).
inline int cross_sign(Point p, Point q, Point r, Point s);
int cross_sign_exact(Point p, Point q, Point r, Point s);

// The floating-point filter shared by the predicates: the sign of left - right when the rounding error
// of the two products and the subtraction (Shewchuk's ccwerrboundA = (3 + 16 eps) eps, eps = 2^-53)
// cannot change it, 0 when the exact evaluation must decide. The bound assumes no underflow: below
// 2^-960 (triangles smaller than about 1e-145) the products' absolute underflow error can exceed it, and
// on overflow (inf, NaN) nothing is decided here either.
// Written without a branch on the data: a sign decided by the data is a branch mispredicted about half the
// time, and clip evaluates nine of them at once.
inline int filtered_sign(double left, double right) {
  const double det = left - right;
  const double bound = 3.3306690738754716e-16 * (std::fabs(left) + std::fabs(right));
  return bound >= 0x1p-960 ? (det > bound) - (-det > bound) : 0;
}

inline int orient2d(Point a, Point b, Point c) {
  const int s = filtered_sign((a.x - c.x) * (b.y - c.y), (a.y - c.y) * (b.x - c.x));
  return s != 0 ? s : orient2d_exact(a, b, c);
}

inline int cross_sign(Point p, Point q, Point r, Point s) {
  const int f = filtered_sign((q.x - p.x) * (s.y - r.y), (q.y - p.y) * (s.x - r.x));
  return f != 0 ? f : cross_sign_exact(p, q, r, s);
}

// A value as m 2^e (m = 0, or 0.5 <= |m| < 1): representable however far below the doubles it lies.
struct ScaledValue {
  double m = 0;
  int e = 0;
};

// x and y as doubles in the units of the larger: m 2^(e - max(e_x, e_y)), so that their ratios are accurate
// (the smaller may vanish against the larger: then it is below round-off of it; a zero has no exponent).
inline void to_common_scale(ScaledValue x, ScaledValue y, double& sx, double& sy) {
  const int e = x.m == 0 ? y.e : (y.m == 0 ? x.e : std::max(x.e, y.e));
  sx = std::ldexp(x.m, x.e - e);
  sy = std::ldexp(y.m, y.e - e);
}

// det [b - a, c - a] with the bound (3 + 16 eps) eps times the permanent plus 2^-1073 (each of the two
// products loses at most 2^-1075 to underflow), and its exact value, rounded, as m 2^e (as orient3d_value's,
// predicates3d.hpp): for points of a plane seen in a coordinate projection (clip3d.cpp).
inline double orient2d_estimate(Point a, Point b, Point c, double& bound) {
  const double l = (b.x - a.x) * (c.y - a.y), r = (b.y - a.y) * (c.x - a.x);
  bound = 3.3306690738754716e-16 * (std::fabs(l) + std::fabs(r)) + 0x1p-1073;
  return l - r;
}
ScaledValue orient2d_value(Point a, Point b, Point c);

}  // namespace dlmfsi
