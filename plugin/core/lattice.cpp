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

void monomials(int d, Point xi, double* value, double* d1, double* d2) {
  double p1[kMaxLatticeDegree + 1], p2[kMaxLatticeDegree + 1];
  p1[0] = p2[0] = 1;
  for (int i = 1; i <= d; ++i) {
    p1[i] = p1[i - 1] * xi.x;
    p2[i] = p2[i - 1] * xi.y;
  }
  int m = 0;
  for (int t = 0; t <= d; ++t)
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b;
      value[m] = p1[a] * p2[b];
      d1[m] = a > 0 ? a * p1[a - 1] * p2[b] : 0.0;
      d2[m] = b > 0 ? b * p1[a] * p2[b - 1] : 0.0;
    }
}

}  // namespace dlmfsi
