// What the searches for symmetric rules share (triangle_rules.cpp, tet_rules_symmetric.cpp, tet_rules.cpp; not part
// of the build): magnitudes and roots in double, long double and __float128, dense linear algebra, Levenberg-
// Marquardt in double and a lightly damped Gauss-Newton in __float128 on a residual given as a function.
#pragma once
#include <quadmath.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace rule_search {

using Quad = __float128;

inline double root(double v) { return std::sqrt(v); }
inline Quad root(Quad v) { return sqrtq(v); }
inline double magnitude(double v) { return std::fabs(v); }
inline long double magnitude(long double v) { return std::fabs(v); }
inline Quad magnitude(Quad v) { return fabsq(v); }

// Solves A x = b (n x n, row-major; b becomes x) by Gaussian elimination with partial pivoting.
template <class T>
bool solve(std::vector<T> a, std::vector<T>& b, int n) {
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (magnitude(a[r * n + c]) > magnitude(a[pivot * n + c])) pivot = r;
    if (!(magnitude(a[pivot * n + c]) > 0)) return false;
    for (int k = 0; k < n; ++k) std::swap(a[c * n + k], a[pivot * n + k]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < n; ++r) {
      const T f = a[r * n + c] / a[c * n + c];
      for (int k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    T s = b[c];
    for (int k = c + 1; k < n; ++k) s -= a[c * n + k] * b[k];
    b[c] = s / a[c * n + c];
  }
  return true;
}

// The normal equations J^T J and the gradient J^T r (zero entries of J skipped: the same sums).
template <class T>
void normal(const std::vector<T>& jac, const std::vector<T>& r, int n, std::vector<T>& a, std::vector<T>& g) {
  const int m = static_cast<int>(r.size());
  a.assign(static_cast<size_t>(n) * n, 0);
  g.assign(n, 0);
  for (int i = 0; i < m; ++i) {
    const T* row = jac.data() + static_cast<size_t>(i) * n;
    for (int p = 0; p < n; ++p) {
      if (row[p] == 0) continue;
      g[p] += row[p] * r[i];
      for (int q = p; q < n; ++q) a[p * n + q] += row[p] * row[q];
    }
  }
  for (int p = 0; p < n; ++p)
    for (int q = 0; q < p; ++q) a[p * n + q] = a[q * n + p];
}

template <class T>
T squares(const std::vector<T>& r) {
  T s = 0;
  for (T v : r) s += v * v;
  return s;
}

template <class T>
T factorial(int n) {
  return n <= 1 ? T(1) : T(n) * factorial<T>(n - 1);
}

inline std::string text(Quad v) {
  char buf[64];
  quadmath_snprintf(buf, sizeof buf, "%.25Qg", v);
  return buf;
}

// Levenberg-Marquardt on the n parameters t of residual(t, r, jac) (jac: r's derivatives, row-major, or null);
// returns the final sum of squares. It stops early where it stalls or where a start looks hopeless.
template <class Residual>
double levenberg_marquardt(int n, const Residual& residual, std::vector<double>& t, int iterations) {
  std::vector<double> r, jac, a, g, rv;
  residual(t, r, &jac);
  double f = squares(r), lambda = 1e-3;
  for (int it = 0; it < iterations && f > 1e-26; ++it) {
    normal(jac, r, n, a, g);
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries) {
      std::vector<double> m = a, step(n);
      for (int p = 0; p < n; ++p) {
        m[p * n + p] += lambda * a[p * n + p] + 1e-14;
        step[p] = -g[p];
      }
      if (!solve(m, step, n)) {
        lambda *= 10;
        continue;
      }
      std::vector<double> v = t;
      for (int p = 0; p < n; ++p) v[p] += step[p];
      residual(v, rv, nullptr);
      const double fv = squares(rv);
      if (fv < f) {
        t = v;
        f = fv;
        residual(t, r, &jac);
        lambda = std::max(lambda / 10, 1e-15);
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved || (it == 100 && f > 1e-6) || (it == 300 && f > 1e-12)) break;  // stuck, or a hopeless start
  }
  return f;
}

// Gauss-Newton in __float128 on the parameters u of residual(u, r, jac), lightly damped (the structure may have
// more unknowns than independent conditions), at most iterations steps; returns the final sum of squares.
template <class Residual>
Quad gauss_newton(int n, const Residual& residual, std::vector<Quad>& u, int iterations) {
  std::vector<Quad> r, jac, a, g;
  residual(u, r, &jac);
  Quad f = squares(r);
  for (int it = 0; it < iterations && f > Quad(1e-66); ++it) {
    normal(jac, r, n, a, g);
    Quad scale = 0;
    for (int p = 0; p < n; ++p) scale = std::max(scale, a[p * n + p]);
    for (int p = 0; p < n; ++p) {
      a[p * n + p] += scale * Quad(1e-40);
      g[p] = -g[p];
    }
    if (!solve(a, g, n)) break;
    std::vector<Quad> v = u, rv;
    for (int p = 0; p < n; ++p) v[p] += g[p];
    residual(v, rv, &jac);
    const Quad fv = squares(rv);
    if (!(fv < f)) break;
    u = v;
    r = rv;
    f = fv;
  }
  return f;
}

// Every node's weight positive and every barycentric coordinate (its l) above min_bary.
template <class Nodes>
bool positive_inside(const Nodes& nodes, Quad min_bary) {
  for (const auto& q : nodes) {
    if (!(q.w > 0)) return false;
    for (Quad l : q.l)
      if (!(l > min_bary)) return false;
  }
  return true;
}

}  // namespace rule_search
