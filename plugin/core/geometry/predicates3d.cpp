#include "geometry/predicates3d.hpp"

#include <cmath>

#include "geometry/exact_sign.hpp"

namespace dlmfsi {

namespace {

// b - a exactly? (the tail of Knuth's two-sum of b and -a is zero)
inline bool exact_difference(double b, double a, double& d) {
  d = b - a;
  const double bv = d - b;
  const double av = d - bv;
  return std::isfinite(d) && (b - av) + (-a - bv) == 0;
}

// The six triple products of det [u, v, w] = u . (v x w).
void triple_products(Point3 u, Point3 v, Point3 w, double sign, double (*f)[3]) {
  const double t[6][3] = {{u.x, v.y, w.z}, {-u.x, v.z, w.y}, {u.y, v.z, w.x},
                          {-u.y, v.x, w.z}, {u.z, v.x, w.y}, {-u.z, v.y, w.x}};
  for (int k = 0; k < 6; ++k) {
    f[k][0] = sign * t[k][0];
    f[k][1] = t[k][1];
    f[k][2] = t[k][2];
  }
}

// The determinant's terms: the six triple products of the exact differences when the nine subtractions
// are exact (often so for the coincident and coplanar points that reach the exact path), else by
// multilinearity det [b - a, c - a, d - a] = D(b, c, d) - D(a, c, d) + D(a, b, d) - D(a, b, c),
// D(p, q, r) = p . (q x r): 24 triple products of the coordinates. Returns the number of terms.
int orient3d_terms(Point3 a, Point3 b, Point3 c, Point3 d, double (*f)[3]) {
  Point3 u, v, w;
  if (exact_difference(b.x, a.x, u.x) && exact_difference(b.y, a.y, u.y) && exact_difference(b.z, a.z, u.z) &&
      exact_difference(c.x, a.x, v.x) && exact_difference(c.y, a.y, v.y) && exact_difference(c.z, a.z, v.z) &&
      exact_difference(d.x, a.x, w.x) && exact_difference(d.y, a.y, w.y) && exact_difference(d.z, a.z, w.z)) {
    triple_products(u, v, w, 1, f);
    return 6;
  }
  triple_products(b, c, d, 1, f);
  triple_products(a, c, d, -1, f + 6);
  triple_products(a, b, d, 1, f + 12);
  triple_products(a, b, c, -1, f + 18);
  return 24;
}

}  // namespace

int orient3d_exact(Point3 a, Point3 b, Point3 c, Point3 d) {
  // Two equal points make two rows of the determinant equal (or one zero): 0 exactly, without the expansion
  // (coincident vertices of two meshes are the common degenerate case).
  if (a == b || a == c || a == d || b == c || b == d || c == d) return 0;
  double f[24][3];
  const int n = orient3d_terms(a, b, c, d, f);
  return exact_sign_of_sum(&f[0][0], n, 3);
}

ScaledValue orient3d_value(Point3 a, Point3 b, Point3 c, Point3 d) {
  double f[24][3];
  const int n = orient3d_terms(a, b, c, d, f);
  ScaledValue v;
  v.m = exact_sum(&f[0][0], n, 3, v.e);
  return v;
}

}  // namespace dlmfsi
