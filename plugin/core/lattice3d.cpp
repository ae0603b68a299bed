#include "lattice3d.hpp"

#include <cmath>
#include <utility>

namespace dlmfsi {

void monomial_exponents3(int m, int& a, int& b, int& c) {
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

Point3 lattice_point3(int d, int m) {
  if (d == 0) return {0.25, 0.25, 0.25};
  int a, b, c;
  monomial_exponents3(m, a, b, c);
  return {static_cast<double>(a) / d, static_cast<double>(b) / d, static_cast<double>(c) / d};
}

namespace {

// The index of the monomial with exponents (a, b, c).
int monomial_index3(int a, int b, int c) {
  const int t = a + b + c;
  int m = t > 0 ? monomial_count3(t - 1) : 0;
  for (int cc = 0; cc < c; ++cc) m += t - cc + 1;
  return m + b;
}

}  // namespace

const std::vector<MonomialDerivative3>& monomial_derivatives3(int d) {
  static const auto table = [] {
    std::vector<std::vector<MonomialDerivative3>> all(kMaxLatticeDegree + 1);
    for (int deg = 0; deg <= kMaxLatticeDegree; ++deg)
      for (int m = 0; m < monomial_count3(deg); ++m) {
        int e[3];
        monomial_exponents3(m, e[0], e[1], e[2]);
        MonomialDerivative3 r{};
        for (int i = 0; i < 3; ++i) {
          if (e[i] == 0) {
            r.index[i] = -1;
            r.factor[i] = 0;
            continue;
          }
          int f[3] = {e[0], e[1], e[2]};
          --f[i];
          r.index[i] = monomial_index3(f[0], f[1], f[2]);
          r.factor[i] = e[i];
        }
        all[deg].push_back(r);
      }
    return all;
  }();
  return table[d];
}

const std::vector<double>& vandermonde_inverse3(int d) {
  static const auto table = [] {
    std::vector<std::vector<double>> inv(kMaxLatticeDegree + 1);
    for (int deg = 0; deg <= kMaxLatticeDegree; ++deg) {
      const int n = monomial_count3(deg), w = 2 * n;
      std::vector<double> a(static_cast<size_t>(n) * w, 0.0);  // [V | I], Gauss-Jordan with pivoting
      std::vector<double> row(n);
      for (int p = 0; p < n; ++p) {
        monomial_values3(deg, lattice_point3(deg, p), row.data());
        for (int m = 0; m < n; ++m) a[static_cast<size_t>(p) * w + m] = row[m];
        a[static_cast<size_t>(p) * w + n + p] = 1;
      }
      for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
          if (std::fabs(a[static_cast<size_t>(r) * w + c]) > std::fabs(a[static_cast<size_t>(piv) * w + c])) piv = r;
        for (int j = 0; j < w; ++j) std::swap(a[static_cast<size_t>(c) * w + j], a[static_cast<size_t>(piv) * w + j]);
        const double diag = a[static_cast<size_t>(c) * w + c];
        for (int j = 0; j < w; ++j) a[static_cast<size_t>(c) * w + j] /= diag;
        for (int r = 0; r < n; ++r) {
          const double f = a[static_cast<size_t>(r) * w + c];
          if (r != c && f != 0)
            for (int j = 0; j < w; ++j) a[static_cast<size_t>(r) * w + j] -= f * a[static_cast<size_t>(c) * w + j];
        }
      }
      inv[deg].resize(static_cast<size_t>(n) * n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) inv[deg][static_cast<size_t>(r) * n + c] = a[static_cast<size_t>(r) * w + n + c];
    }
    return inv;
  }();
  return table[d];
}

}  // namespace dlmfsi
