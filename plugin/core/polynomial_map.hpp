// A polynomial map of the plane in monomial form, X(xi) = sum over the monomials m = xi1^a xi2^b (lattice.hpp
// order: by t = a + b, then b) of (cx_m, cy_m), evaluated with its derivatives in xi1 and xi2.
#pragma once
#include "lattice.hpp"

namespace dlmfsi {

constexpr int kMaxPolynomialMapDegree = 6;

// x = X(xi), dx1 = dX/dxi1 and dx2 = dX/dxi2 from the coefficients cx, cy of degree D >= 0 (constant: the
// loops unroll) or, for D < 0, of the run-time degree d.
template <int D>
void evaluate_polynomial(int d, const double* cx, const double* cy, Point xi, Point& x, Point& dx1, Point& dx2) {
  const int degree = D >= 0 ? D : d;
  double p1[kMaxPolynomialMapDegree + 1], p2[kMaxPolynomialMapDegree + 1];
  powers(degree, xi, p1, p2);
  // d/dxi1 xi1^a xi2^b = a xi1^(a-1) xi2^b, d/dxi2 xi1^a xi2^b = b xi1^a xi2^(b-1).
  // Local sums: the outputs may alias memory the compiler cannot keep in registers.
  double x0 = cx[0], x1 = cy[0], a0 = 0, a1 = 0, b0 = 0, b1 = 0;
  int m = 1;
#pragma GCC unroll 8
  for (int t = 1; t <= degree; ++t) {
#pragma GCC unroll 8
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b;
      const double v = p1[a] * p2[b];
      x0 += cx[m] * v;
      x1 += cy[m] * v;
      if (a > 0) {
        const double g = a * p1[a - 1] * p2[b];
        a0 += cx[m] * g;
        a1 += cy[m] * g;
      }
      if (b > 0) {
        const double g = b * p1[a] * p2[b - 1];
        b0 += cx[m] * g;
        b1 += cy[m] * g;
      }
    }
  }
  x = {x0, x1};
  dx1 = {a0, a1};
  dx2 = {b0, b1};
}

}  // namespace dlmfsi
