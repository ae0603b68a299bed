#include "polynomial_values3d.hpp"

#include <algorithm>
#include <vector>

#include "lattice3d.hpp"
#include "polynomial_fit.hpp"

namespace dlmfsi {

void evaluate_polynomials3(int degree, const double* coef, size_t width, const int* twin, const double* j,
                           const Point3* xi, int n, double* value, double* gradient) {
  const int nm = monomial_count3(degree);
  const auto& derivative = monomial_derivatives3(degree);
  const int nm1 = degree > 0 ? monomial_count3(degree - 1) : 0;
  // Monomial-major: mono[m * n + p] is monomial m at point p, so that each function's sums run along the
  // points.
  thread_local std::vector<double> scratch, ref;
  if (scratch.size() < static_cast<size_t>(nm) * n) scratch.resize(static_cast<size_t>(nm) * n);
  double* mono = scratch.data();
  for (int p = 0; p < n; ++p) {
    double v[monomial_count3(kMaxLatticeDegree)];
    monomial_values3(degree, xi[p], v);
    for (int m = 0; m < nm; ++m) mono[static_cast<size_t>(m) * n + p] = v[m];
  }
  if (gradient && ref.size() < 3 * static_cast<size_t>(nm1 > 0 ? nm1 : 1))
    ref.resize(3 * static_cast<size_t>(nm1 > 0 ? nm1 : 1));
  for (size_t f = 0; f < width; ++f) {
    if (twin && twin[f] >= 0) continue;  // copied below
    const double* c = coef + f * nm;
    sum_monomials(c, nm, mono, n, value + f * n);
    if (!gradient) continue;
    // the reference derivatives' coefficients on the degree - 1 monomials
    double* e = ref.data();
    std::fill(e, e + 3 * nm1, 0.0);
    for (int m = 1; m < nm; ++m)
      for (int i = 0; i < 3; ++i)
        if (derivative[m].index[i] >= 0) e[i * nm1 + derivative[m].index[i]] += derivative[m].factor[i] * c[m];
    double* g[3] = {gradient + (3 * f) * n, gradient + (3 * f + 1) * n, gradient + (3 * f + 2) * n};
    for (int p = 0; p < n; ++p) {
      double r[3] = {0, 0, 0};
      for (int m = 0; m < nm1; ++m) {
        const double mp = mono[static_cast<size_t>(m) * n + p];
        r[0] += e[m] * mp;
        r[1] += e[nm1 + m] * mp;
        r[2] += e[2 * nm1 + m] * mp;
      }
      // d phi / d x_j = sum_i d phi / d xi_i  d xi_i / d x_j
      for (int a = 0; a < 3; ++a) g[a][p] = r[0] * j[a] + r[1] * j[3 + a] + r[2] * j[6 + a];
    }
  }
  if (!twin) return;
  for (size_t f = 0; f < width; ++f) {
    const int t = twin[f];
    if (t < 0) continue;
    std::copy(value + t * n, value + (t + 1) * n, value + f * n);
    if (gradient) std::copy(gradient + 3 * t * n, gradient + 3 * (t + 1) * n, gradient + 3 * f * n);
  }
}

}  // namespace dlmfsi
