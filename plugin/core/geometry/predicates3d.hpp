// Exact geometric predicates in space.
#pragma once
#include <algorithm>
#include <cmath>

#include "point3.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

// Sign of det [b - a, c - a, d - a]: +1 when (a, b, c, d) is a positively oriented tetrahedron (d on the
// side of the plane through a, b, c toward which (b - a) x (c - a) points: a, b, c turn counter-clockwise
// seen from d), -1 for the other side, 0 exactly when the four points are coplanar.
// Exact for all finite inputs. Degenerate cases that give 0, exactly: two or more coincident points, three
// collinear points, four coplanar points (a point on a face plane, an edge crossing an edge, coplanar
// faces); a point perturbed off them by one ulp gets the sign of the perturbation, never 0. Coordinates may
// range from subnormals to the largest doubles, mixed within one call. A floating-point filter decides
// the common case; otherwise the determinant of the exact differences (when the nine subtractions are
// exact) or of the 24 triple products of the coordinates is evaluated exactly (exact_sign.hpp). Inputs
// that are not finite give 0 (outside the contract).
inline int orient3d(Point3 a, Point3 b, Point3 c, Point3 d);

// The same determinant evaluated exactly, without the floating-point filter.
int orient3d_exact(Point3 a, Point3 b, Point3 c, Point3 d);

// The error bound of the floating-point determinant below: Shewchuk's o3derrboundA = (7 + 56 eps) eps
// (eps = 2^-53) times the permanent, plus 2^-1072 (1 + |u|_1) for products that underflow (each 2 x 2 minor
// of c - a and d - a loses at most 2^-1074 to underflow before it is multiplied by a component of u = b - a,
// and each of those three products 2^-1075 more; sums of subnormal numbers are exact). s = 1 + |u|_1.
// Where permanent >= 2^-900 s the underflow term is below 2^-121 of the first, and the first with its
// constant raised by 2^-40 covers both; below that (only for tiny coordinates or differences) +inf: the exact
// evaluation decides. So the bound never multiplies a subnormal number (about 50 ns on this machine's Xeon,
// against 1 ns). Inf or NaN input gives inf or NaN.
constexpr double kOrient3dRelativeBound = 7.7715611723761e-16 * (1 + 0x1p-40);
inline double orient3d_bound(double permanent, double s) {
  return permanent >= 0x1p-900 * s ? kOrient3dRelativeBound * permanent
                                   : (permanent == permanent ? HUGE_VAL : permanent);
}

// The determinant det [b - a, c - a, d - a] in floating point, and a bound on its error (orient3d_bound).
inline double orient3d_estimate(Point3 a, Point3 b, Point3 c, Point3 d, double& bound) {
  const Point3 u = b - a, v = c - a, w = d - a;
  const double t1 = v.y * w.z, t2 = v.z * w.y, t3 = v.z * w.x, t4 = v.x * w.z, t5 = v.x * w.y, t6 = v.y * w.x;
  const double det = u.x * (t1 - t2) + u.y * (t3 - t4) + u.z * (t5 - t6);
  const double ax = std::fabs(u.x), ay = std::fabs(u.y), az = std::fabs(u.z);
  const double permanent = ax * (std::fabs(t1) + std::fabs(t2)) + ay * (std::fabs(t3) + std::fabs(t4)) +
                           az * (std::fabs(t5) + std::fabs(t6));
  bound = orient3d_bound(permanent, 1 + ax + ay + az);
  return det;
}

// The filter: the sign of the estimate when its error bound cannot change it, 0 when the exact evaluation
// must decide (also on overflow: inf, NaN).
inline int orient3d_filter(Point3 a, Point3 b, Point3 c, Point3 d) {
  double bound;
  const double det = orient3d_estimate(a, b, c, d, bound);
  return (det > bound) - (-det > bound);  // without branches: the sign is data, not predictable
}

// det [b - a, c - a, d - a] exactly, rounded (a few ulps; 0 exactly when it is 0), as m 2^e: accurate for
// determinants below the doubles too (subnormal coordinates, points one ulp apart), where a double would
// keep few bits or none. For constructions whose floating-point evaluation cancels (a ratio of two).
ScaledValue orient3d_value(Point3 a, Point3 b, Point3 c, Point3 d);

inline int orient3d(Point3 a, Point3 b, Point3 c, Point3 d) {
  const int s = orient3d_filter(a, b, c, d);
  return s != 0 ? s : orient3d_exact(a, b, c, d);
}

// The plane through p, q, r prepared for many tests: sign(x) = orient3d(p, q, r, x), exactly, with the
// filter's 2 x 2 minors of q - p, r - p formed once. The filter is orient3d's (the same products, the
// same bound: each term a difference times a minor of the other two differences), the exact path too.
struct PlaneSide {
  Point3 p, q, r;
  Point3 n, pn;  // the minors' differences (q - p) x (r - p) and the sums of their absolute values
  void set(Point3 a, Point3 b, Point3 c) {
    p = a;
    q = b;
    r = c;
    const Point3 u = b - a, v = c - a;
    const double t1 = u.y * v.z, t2 = u.z * v.y, t3 = u.z * v.x, t4 = u.x * v.z, t5 = u.x * v.y, t6 = u.y * v.x;
    n = {t1 - t2, t3 - t4, t5 - t6};
    pn = {std::fabs(t1) + std::fabs(t2), std::fabs(t3) + std::fabs(t4), std::fabs(t5) + std::fabs(t6)};
  }
  int sign(Point3 x) const {
    const int s = filter(x);
    return s != 0 ? s : orient3d_exact(p, q, r, x);
  }
  // The filter alone: the sign when the floating-point estimate decides it, else 0 (then sign() is exact).
  int filter(Point3 x) const {
    double bound;
    const double det = estimate(x, bound);
    return (det > bound) - (-det > bound);  // without branches: the sign is data, not predictable
  }
  // orient3d(p, q, r, x) in floating point and the bound on its error (orient3d_estimate's, the same value).
  double estimate(Point3 x, double& bound) const {
    const Point3 w = x - p;
    const double det = w.x * n.x + w.y * n.y + w.z * n.z;
    const double ax = std::fabs(w.x), ay = std::fabs(w.y), az = std::fabs(w.z);
    const double permanent = ax * pn.x + ay * pn.y + az * pn.z;
    bound = orient3d_bound(permanent, 1 + ax + ay + az);
    return det;
  }
};

// Orientation of the projections of a, b, c onto the coordinate plane that drops axis (0: x, 1: y, 2: z),
// as orient2d on (y, z), (z, x) and (x, y) respectively: for points of a plane whose normal has a non-zero
// component along axis, the orientation within that plane (up to that component's sign). Exact.
inline int orient2d_projected(Point3 a, Point3 b, Point3 c, int axis) {
  auto drop = [axis](Point3 p) { return axis == 0 ? Point{p.y, p.z} : axis == 1 ? Point{p.z, p.x} : Point{p.x, p.y}; };
  return orient2d(drop(a), drop(b), drop(c));
}

}  // namespace dlmfsi
