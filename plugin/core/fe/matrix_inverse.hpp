// The inverse of a small dense matrix (the lattices' Vandermonde and Bernstein matrices).
#pragma once
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace dlmfsi {

// The inverse of the n x n matrix m (row-major), by Gauss-Jordan elimination on [m | I] with partial
// pivoting.
inline std::vector<double> inverse(const std::vector<double>& m, int n) {
  const int w = 2 * n;
  std::vector<double> a(static_cast<std::size_t>(n) * w, 0.0);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) a[static_cast<std::size_t>(r) * w + c] = m[static_cast<std::size_t>(r) * n + c];
    a[static_cast<std::size_t>(r) * w + n + r] = 1;
  }
  auto at = [&](int r, int c) -> double& { return a[static_cast<std::size_t>(r) * w + c]; };
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(at(r, c)) > std::fabs(at(piv, c))) piv = r;
    for (int j = 0; j < w; ++j) std::swap(at(c, j), at(piv, j));
    const double diag = at(c, c);
    for (int j = 0; j < w; ++j) at(c, j) /= diag;
    for (int r = 0; r < n; ++r) {
      const double f = at(r, c);
      if (r != c && f != 0)
        for (int j = 0; j < w; ++j) at(r, j) -= f * at(c, j);
    }
  }
  std::vector<double> inv(static_cast<std::size_t>(n) * n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) inv[static_cast<std::size_t>(r) * n + c] = at(r, n + c);
  return inv;
}

}  // namespace dlmfsi
