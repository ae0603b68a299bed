// The inverse of a small dense matrix (the lattices' Vandermonde and Bernstein matrices).
#pragma once
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "point3.hpp"

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

// The inverse of the 3 x 3 matrix with columns e1, e2, e3: rows (e2 x e3, e3 x e1, e1 x e2) / det.
inline void inverse_of_columns(Point3 e1, Point3 e2, Point3 e3, double inv[3][3]) {
  const double det = dot(e1, cross(e2, e3));
  const Point3 rows[3] = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
  for (int r = 0; r < 3; ++r) {
    inv[r][0] = rows[r].x / det;
    inv[r][1] = rows[r].y / det;
    inv[r][2] = rows[r].z / det;
  }
}

}  // namespace dlmfsi
