#include "lattice.hpp"

#include <cmath>
#include <utility>

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

const std::vector<double>& vandermonde_inverse(int d) {
  static const auto table = [] {
    std::vector<std::vector<double>> inv(kMaxLatticeDegree + 1);
    for (int deg = 0; deg <= kMaxLatticeDegree; ++deg) {
      const int n = monomial_count(deg), w = 2 * n;
      std::vector<double> a(static_cast<size_t>(n) * w, 0.0);  // [V | I], Gauss-Jordan with pivoting
      for (int p = 0; p < n; ++p) {
        const Point x = lattice_point(deg, p);
        for (int m = 0; m < n; ++m) {
          int ea, eb;
          monomial_exponents(m, ea, eb);
          a[p * w + m] = std::pow(x.x, ea) * std::pow(x.y, eb);
        }
        a[p * w + n + p] = 1;
      }
      for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
          if (std::fabs(a[r * w + c]) > std::fabs(a[piv * w + c])) piv = r;
        for (int j = 0; j < w; ++j) std::swap(a[c * w + j], a[piv * w + j]);
        const double diag = a[c * w + c];
        for (int j = 0; j < w; ++j) a[c * w + j] /= diag;
        for (int r = 0; r < n; ++r) {
          const double f = a[r * w + c];
          if (r != c && f != 0)
            for (int j = 0; j < w; ++j) a[r * w + j] -= f * a[c * w + j];
        }
      }
      inv[deg].resize(static_cast<size_t>(n) * n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) inv[deg][r * n + c] = a[r * w + n + c];
    }
    return inv;
  }();
  return table[d];
}

}  // namespace dlmfsi
