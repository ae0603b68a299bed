#include "fe/lattice.hpp"

#include <cmath>
#include <mutex>
#include <utility>

#include "fe/matrix_inverse.hpp"

namespace dlmfsi {

void monomial_exponents(int m, int& a, int& b) {
  int t = 0;
  while (monomial_count(t) <= m) ++t;
  b = m - monomial_count(t - 1);
  a = t - b;
}

Point lattice_point(int d, int m) {
  if (d == 0) return {1.0 / 3, 1.0 / 3};
  int a, b;
  monomial_exponents(m, a, b);
  return {static_cast<double>(a) / d, static_cast<double>(b) / d};
}

// Each degree's inverse on first use (std::call_once: threads may ask together), not all of them at once.
const std::vector<double>& vandermonde_inverse(int d) {
  static std::vector<double> inv[kMaxLatticeDegree + 1];
  static std::once_flag made[kMaxLatticeDegree + 1];
  std::call_once(made[d], [d] {
    const int n = monomial_count(d);
    std::vector<double> v(static_cast<size_t>(n) * n);  // V[p][m] = monomial m at lattice point p
    for (int p = 0; p < n; ++p) {
      const Point x = lattice_point(d, p);
      for (int m = 0; m < n; ++m) {
        int ea, eb;
        monomial_exponents(m, ea, eb);
        v[p * n + m] = std::pow(x.x, ea) * std::pow(x.y, eb);
      }
    }
    inv[d] = inverse(v, n);
  });
  return inv[d];
}

}  // namespace dlmfsi
