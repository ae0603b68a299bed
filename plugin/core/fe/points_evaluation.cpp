#include "fe/points_evaluation.hpp"

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <vector>

#include "fe/lattice.hpp"
#include "fe/polynomial_fit.hpp"

namespace dlmfsi {

namespace {

// NM > 0: the monomial count of a constant degree (the loops unroll); NM = 0: fit.terms().
template <int NM>
void evaluate_fitted(const BasisFit& fit, int k, const double* j, const Point* xi, int n, double* value,
                     double* dx, double* dy) {
  // Monomial-major: mono[m * n + p] is monomial m at point p, so that each function's sums run along the
  // points (vectorizable); the derivatives come from the derivative polynomials' coefficients (degree - 1).
  constexpr int kDegree = NM == 1 ? 0 : NM == 3 ? 1 : NM == 6 ? 2 : NM == 10 ? 3 : -1;
  const int degree = kDegree >= 0 ? kDegree : fit.degree();
  const int nm = NM > 0 ? NM : fit.terms();
  const int nm1 = monomial_count(degree - 1);
  const size_t width = fit.functions().size();
  const double* coef = fit.coefficients(k);
  const double* deriv = fit.derivative_coefficients(k);
  const bool shared = fit.shared(k);
  thread_local std::vector<double> scratch, reference;
  if (scratch.size() < static_cast<size_t>(nm) * n) scratch.resize(static_cast<size_t>(nm) * n);
  if (dx && reference.size() < 2 * static_cast<size_t>(n)) reference.resize(2 * static_cast<size_t>(n));
  double* mono = scratch.data();
  for (int p = 0; p < n; ++p) {
    double v[monomial_count(kMaxLatticeDegree)];
    monomial_values(degree, xi[p], v);
    for (int m = 0; m < nm; ++m) mono[static_cast<size_t>(m) * n + p] = v[m];
  }
  for (size_t f = 0; f < width; ++f) {
    if (shared && fit.twin(static_cast<int>(f)) >= 0) continue;
    sum_monomials(coef + f * nm, nm, mono, n, value + f * n);
    if (!dx) continue;
    // the reference derivatives along the points, then the physical ones through j = d xi / d x
    const double *e1 = deriv + f * 2 * nm1, *e2 = e1 + nm1;
    double *g1 = reference.data(), *g2 = g1 + n;
    if (nm1 == 0) {  // degree 0
      std::fill(g1, g1 + 2 * n, 0.0);
    } else {
      sum_monomials(e1, nm1, mono, n, g1);
      sum_monomials(e2, nm1, mono, n, g2);
    }
    double *gx = dx + f * n, *gy = dy + f * n;
    for (int p = 0; p < n; ++p) {
      gx[p] = g1[p] * j[0] + g2[p] * j[2];
      gy[p] = g1[p] * j[1] + g2[p] * j[3];
    }
  }
  // the twins' rows: copies of the rows they repeat
  if (!shared) return;
  for (size_t f = 0; f < width; ++f) {
    const int twin = fit.twin(static_cast<int>(f));
    if (twin >= 0)
      for (double* plane : {value, dx, dy})
        if (plane) std::copy(plane + twin * n, plane + (twin + 1) * n, plane + f * n);
  }
}

}  // namespace

void evaluate_at_points(const BasisFit& fit, int k, const double* inverse_jacobian, const Point* xi, int n,
                        double* value, double* dx, double* dy) {
  switch (fit.degree()) {
    case 0: evaluate_fitted<1>(fit, k, inverse_jacobian, xi, n, value, dx, dy); break;
    case 1: evaluate_fitted<3>(fit, k, inverse_jacobian, xi, n, value, dx, dy); break;
    case 2: evaluate_fitted<6>(fit, k, inverse_jacobian, xi, n, value, dx, dy); break;
    case 3: evaluate_fitted<10>(fit, k, inverse_jacobian, xi, n, value, dx, dy); break;
    default: evaluate_fitted<0>(fit, k, inverse_jacobian, xi, n, value, dx, dy); break;
  }
}

}  // namespace dlmfsi
