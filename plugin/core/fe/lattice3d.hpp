// Polynomials on the reference tetrahedron: monomials xi1^a xi2^b xi3^c (a + b + c <= d) and
// interpolation on the equispaced lattice of degree d, used to turn a basis or a map into a cheap
// polynomial on one tetrahedron (the 3D counterpart of lattice.hpp).
#pragma once
#include <vector>

#include "fe/lattice.hpp"
#include "point3.hpp"

namespace dlmfsi {

constexpr int monomial_count3(int d) { return (d + 1) * (d + 2) * (d + 3) / 6; }

// Monomial m is xi1^a xi2^b xi3^c, listed by total degree t = a + b + c, then c = 0..t, then b = 0..t-c:
// the monomials of degree <= d - 1 are the first monomial_count3(d - 1) of those of degree <= d.
// (Inline: the bands' terms call both for every monomial of every fluid tetrahedron's sums.)
inline void monomial_exponents3(int m, int& a, int& b, int& c) {
  int t = 0;
  while (monomial_count3(t) <= m) ++t;
  int r = m - (t > 0 ? monomial_count3(t - 1) : 0);
  c = 0;
  while (r > t - c) {  // t - c + 1 monomials for each c
    r -= t - c + 1;
    ++c;
  }
  b = r;
  a = t - b - c;
}
// Its inverse: the index of xi1^a xi2^b xi3^c.
inline int monomial_index3(int a, int b, int c) {
  const int t = a + b + c;
  int m = t > 0 ? monomial_count3(t - 1) : 0;
  for (int cc = 0; cc < c; ++cc) m += t - cc + 1;
  return m + b;
}

// Lattice point m of degree d >= 1: (a/d, b/d, c/d) with the exponents of monomial m (d = 0: the centroid).
Point3 lattice_point3(int d, int m);

// Row-major inverse of the Vandermonde matrix V[p][m] = monomial m at lattice point p.
const std::vector<double>& vandermonde_inverse3(int d);

// For the derivatives: derivative[m][i] is the index of d/dxi_i of monomial m in the list of degree d - 1
// (with factor the exponent), or -1 when that exponent is 0.
struct MonomialDerivative3 {
  int index[3];
  double factor[3];
};
const std::vector<MonomialDerivative3>& monomial_derivatives3(int d);

// Monomial m >= 4 (degree >= 2) is monomial parent times xi_(axis + 1): xi1 when its exponent of xi1 is
// positive, else xi2 when that one is, else xi3 (a prefix of the list serves every degree).
struct MonomialParent3 {
  int parent, axis;
};
const std::vector<MonomialParent3>& monomial_parents3();

// Values of all monomials of degree <= d at xi.
inline void monomial_values3(int d, Point3 xi, double* value) {
  double p1[kMaxLatticeDegree + 1], p2[kMaxLatticeDegree + 1], p3[kMaxLatticeDegree + 1];
  p1[0] = p2[0] = p3[0] = 1;
  for (int i = 1; i <= d; ++i) {
    p1[i] = p1[i - 1] * xi.x;
    p2[i] = p2[i - 1] * xi.y;
    p3[i] = p3[i - 1] * xi.z;
  }
  int m = 0;
  for (int t = 0; t <= d; ++t)
    for (int c = 0; c <= t; ++c)
      for (int b = 0; b + c <= t; ++b, ++m) value[m] = p1[t - b - c] * p2[b] * p3[c];
}

}  // namespace dlmfsi
