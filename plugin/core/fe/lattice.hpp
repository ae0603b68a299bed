// Polynomials on the reference triangle: monomials xi1^a xi2^b (a + b <= d) and interpolation on the
// equispaced lattice of degree d, used to turn a basis or a map into a cheap polynomial on one triangle.
#pragma once
#include <vector>

#include "point.hpp"

namespace dlmfsi {

constexpr int kMaxLatticeDegree = 8;
constexpr int monomial_count(int d) { return (d + 1) * (d + 2) / 2; }

// Monomial m is xi1^a xi2^b, listed by total degree t = a + b, then b = 0..t.
void monomial_exponents(int m, int& a, int& b);

// Lattice point m of degree d >= 1: (a/d, b/d) with the exponents of monomial m (d = 0: the centroid).
Point lattice_point(int d, int m);

// Row-major inverse of the Vandermonde matrix V[p][m] = monomial m at lattice point p: the monomial
// coefficients of a polynomial of degree d are inverse * (its values at the lattice points).
const std::vector<double>& vandermonde_inverse(int d);

// The powers xi1^i and xi2^i, i = 0..d.
inline void powers(int d, Point xi, double* p1, double* p2) {
  p1[0] = p2[0] = 1;
#pragma GCC unroll 8
  for (int i = 1; i <= d; ++i) {
    p1[i] = p1[i - 1] * xi.x;
    p2[i] = p2[i - 1] * xi.y;
  }
}

// Values of all monomials of degree <= d at xi (inline, as the next: with a constant d the loops unroll).
inline void monomial_values(int d, Point xi, double* value) {
  double p1[kMaxLatticeDegree + 1], p2[kMaxLatticeDegree + 1];
  powers(d, xi, p1, p2);
  int m = 0;
#pragma GCC unroll 9
  for (int t = 0; t <= d; ++t)
#pragma GCC unroll 9
    for (int b = 0; b <= t; ++b, ++m) value[m] = p1[t - b] * p2[b];
}

// Values of all monomials of degree <= d at xi, and their derivatives in xi1 and xi2.
inline void monomials(int d, Point xi, double* value, double* d1, double* d2) {
  double p1[kMaxLatticeDegree + 1], p2[kMaxLatticeDegree + 1];
  powers(d, xi, p1, p2);
  int m = 0;
#pragma GCC unroll 9
  for (int t = 0; t <= d; ++t)
#pragma GCC unroll 9
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b;
      value[m] = p1[a] * p2[b];
      d1[m] = a > 0 ? a * p1[a - 1] * p2[b] : 0.0;
      d2[m] = b > 0 ? b * p1[a] * p2[b - 1] : 0.0;
    }
}

}  // namespace dlmfsi
