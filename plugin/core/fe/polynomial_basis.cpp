#include "fe/polynomial_basis.hpp"

#include "fe/polynomial_fit.hpp"

namespace dlmfsi {

PolynomialBasis::PolynomialBasis(const Basis& basis, const Mesh& mesh, int degree, const std::vector<int>& components)
    : basis_(basis), maps_(mesh), fit_(basis, mesh.size(), degree, components) {
  if (!fit_.fitted()) return;
  // Confirm the fit reproduces the basis (values and derivatives) off the lattice.
  std::vector<double> sample(static_cast<size_t>(basis.local_dofs()) * basis.components() * 3), check(sample.size());
  if (!fit_reproduces(basis_, {Point{0.137, 0.291}, Point{0.52, 0.083}},
                      [&](Point xi, double* out) { evaluate(0, xi, out); }, fit_.functions(), sample.data(),
                      check.data())) {
    fit_.give_up();
    return;
  }
  fit_.fit_elements(mesh.size());
}

template <int NM>
void PolynomialBasis::evaluate_fitted(const double* coef, const double* j, const double* v, const double* d1,
                                      const double* d2, double* out) const {
  // value = sum_m c_m v_m; d/dx = (sum_m c_m d1_m) dxi1/dx + (sum_m c_m d2_m) dxi2/dx, likewise d/dy
  const int nm = NM > 0 ? NM : fit_.terms();
  for (int f : fit_.functions()) {
    double val = 0, g1 = 0, g2 = 0;
    for (int m = 0; m < nm; ++m) {
      val += coef[m] * v[m];
      g1 += coef[m] * d1[m];
      g2 += coef[m] * d2[m];
    }
    coef += nm;
    double* o = out + f * 3;
    o[0] = val;
    o[1] = g1 * j[0] + g2 * j[2];
    o[2] = g1 * j[1] + g2 * j[3];
  }
}

void PolynomialBasis::evaluate(int k, Point xi, double* out) const {
  if (!fit_.fitted()) {
    basis_.evaluate(k, xi, out);
    return;
  }
  const double* coef = fit_.coefficients(k);
  const double* j = maps_.inverse_jacobian(k);
  double v[monomial_count(kMaxLatticeDegree)], d1[monomial_count(kMaxLatticeDegree)], d2[monomial_count(kMaxLatticeDegree)];
  monomials(fit_.degree(), xi, v, d1, d2);
  // Fixed trip counts for the common degrees let the compiler unroll the sums.
  switch (fit_.degree()) {
    case 1: evaluate_fitted<3>(coef, j, v, d1, d2, out); break;
    case 2: evaluate_fitted<6>(coef, j, v, d1, d2, out); break;
    case 3: evaluate_fitted<10>(coef, j, v, d1, d2, out); break;
    default: evaluate_fitted<0>(coef, j, v, d1, d2, out); break;
  }
}

}  // namespace dlmfsi
