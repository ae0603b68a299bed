// A polynomial map of the plane in monomial form, X(xi) = sum over the monomials m = xi1^a xi2^b (lattice.hpp
// order: by t = a + b, then b) of (cx_m, cy_m), evaluated with its derivatives in xi1 and xi2.
#pragma once
#include "fe/lattice.hpp"

namespace dlmfsi {

constexpr int kMaxPolynomialMapDegree = 6;

// The coefficients of dX/dxi1 and dX/dxi2 (degree d - 1, the same monomial order) from those of X (degree
// d >= 1): d/dxi1 xi1^a xi2^b = a xi1^(a-1) xi2^b, d/dxi2 xi1^a xi2^b = b xi1^a xi2^(b-1).
inline void derive_polynomial(int d, const double* c, double* d1, double* d2) {
  const int n1 = monomial_count(d - 1);
  for (int m = 0; m < n1; ++m) d1[m] = d2[m] = 0;
  int m = 1;
  for (int t = 1; t <= d; ++t)
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b, below = (t - 1) * t / 2;  // the first monomial of degree t - 1
      if (a > 0) d1[below + b] = a * c[m];
      if (b > 0) d2[below + b - 1] = b * c[m];
    }
}

// The coefficients of X of degree d and of its derivatives (derive_polynomial), each monomial's (x, y) pair
// side by side so that a monomial's term is one vector multiply-add. Not initialized: set() fills them.
struct PolynomialMapCoefficients {
  static constexpr int kTerms = monomial_count(kMaxPolynomialMapDegree);
  static constexpr int kDerivativeTerms = monomial_count(kMaxPolynomialMapDegree - 1);
  double x[2 * kTerms], d1[2 * kDerivativeTerms], d2[2 * kDerivativeTerms];
  // From the coefficients cx, cy of X and Y (degree d, 1 <= d <= kMaxPolynomialMapDegree).
  void set(int d, const double* cx, const double* cy) {
    if (d == 1) {  // X = c0 + c1 xi1 + c2 xi2: constant derivatives
      x[0] = cx[0], x[1] = cy[0], x[2] = cx[1], x[3] = cy[1], x[4] = cx[2], x[5] = cy[2];
      d1[0] = cx[1], d1[1] = cy[1], d2[0] = cx[2], d2[1] = cy[2];
      return;
    }
    const int n = monomial_count(d), n1 = monomial_count(d - 1);
    for (int m = 0; m < n; ++m) {
      x[2 * m] = cx[m];
      x[2 * m + 1] = cy[m];
    }
    double e1x[kDerivativeTerms], e1y[kDerivativeTerms], e2x[kDerivativeTerms], e2y[kDerivativeTerms];
    derive_polynomial(d, cx, e1x, e2x);
    derive_polynomial(d, cy, e1y, e2y);
    for (int m = 0; m < n1; ++m) {
      d1[2 * m] = e1x[m];
      d1[2 * m + 1] = e1y[m];
      d2[2 * m] = e2x[m];
      d2[2 * m + 1] = e2y[m];
    }
  }
};

// x = X(xi), dx1 = dX/dxi1 and dx2 = dX/dxi2 from the coefficients c of degree D (1 <= D <=
// kMaxPolynomialMapDegree, a constant: the loops unroll): the monomials' values once, then three sums of terms.
// Scalar code for GCC: its vectorized powers need the pair (xi1, xi2), which it builds by storing the Point
// argument's two halves (passed in two registers) to the stack and loading them back as one 16-byte word, a
// store-forwarding stall on every call (a third of this function's time in the 2D listing's Newton pull-back;
// the results are the same, the operations being the same element by element).
#if defined(__GNUC__) && !defined(__clang__)
#define DLMFSI_SCALAR_CODE __attribute__((optimize("no-tree-slp-vectorize")))
#else
#define DLMFSI_SCALAR_CODE
#endif

// The sums of the terms of X and of its derivatives (degree D) at a point where the monomials take the values
// v: out = (X, Y, dX/dxi1, dY/dxi1, dX/dxi2, dY/dxi2), each summed from 0 in the monomials' order.
template <int D>
inline void sum_map_terms(const PolynomialMapCoefficients& c, const double* v, double out[6]) {
  constexpr int n = monomial_count(D), n1 = monomial_count(D - 1);
  // Local sums: the outputs may alias memory the compiler cannot keep in registers.
  double x0 = 0, x1 = 0, a0 = 0, a1 = 0, b0 = 0, b1 = 0;
#pragma GCC unroll 28
  for (int m = 0; m < n; ++m) {
    x0 += c.x[2 * m] * v[m];
    x1 += c.x[2 * m + 1] * v[m];
  }
#pragma GCC unroll 21
  for (int m = 0; m < n1; ++m) {
    a0 += c.d1[2 * m] * v[m];
    a1 += c.d1[2 * m + 1] * v[m];
    b0 += c.d2[2 * m] * v[m];
    b1 += c.d2[2 * m + 1] * v[m];
  }
  out[0] = x0;
  out[1] = x1;
  out[2] = a0;
  out[3] = a1;
  out[4] = b0;
  out[5] = b1;
}

template <int D>
DLMFSI_SCALAR_CODE
void evaluate_polynomial(const PolynomialMapCoefficients& c, Point xi, Point& x, Point& dx1, Point& dx2) {
  static_assert(D >= 1 && D <= kMaxPolynomialMapDegree, "a polynomial map's degree");
  double v[monomial_count(D)], s[6];
  monomial_values(D, xi, v);
  sum_map_terms<D>(c, v, s);
  x = {s[0], s[1]};
  dx1 = {s[2], s[3]};
  dx2 = {s[4], s[5]};
}

// evaluate_polynomial<D> at n points xi = (xi1[p], xi2[p]), the results as arrays (x, y: X; a0, a1: dX/dxi1;
// b0, b1: dX/dxi2; eight arrays that do not overlap): the same operations point by point, so the same values,
// with the loop over the points vectorized.
template <int D>
void evaluate_polynomial_points(const PolynomialMapCoefficients& c, int n, const double* __restrict xi1,
                                const double* __restrict xi2, double* __restrict x, double* __restrict y,
                                double* __restrict a0, double* __restrict a1, double* __restrict b0,
                                double* __restrict b1) {
  static_assert(D >= 1 && D <= kMaxPolynomialMapDegree, "a polynomial map's degree");
  constexpr int nm = monomial_count(D);
  for (int p = 0; p < n; ++p) {
    // monomial_values(D, xi, v), written out on scalars so that the loop over the points vectorizes
    double p1[D + 1], p2[D + 1], v[nm], s[6];
    p1[0] = p2[0] = 1;
#pragma GCC unroll 8
    for (int i = 1; i <= D; ++i) {
      p1[i] = p1[i - 1] * xi1[p];
      p2[i] = p2[i - 1] * xi2[p];
    }
    int k = 0;
#pragma GCC unroll 9
    for (int t = 0; t <= D; ++t)
#pragma GCC unroll 9
      for (int b = 0; b <= t; ++b, ++k) v[k] = p1[t - b] * p2[b];
    sum_map_terms<D>(c, v, s);
    x[p] = s[0];
    y[p] = s[1];
    a0[p] = s[2];
    a1[p] = s[3];
    b0[p] = s[4];
    b1[p] = s[5];
  }
}

}  // namespace dlmfsi
