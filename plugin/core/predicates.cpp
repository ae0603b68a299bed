#include "predicates.hpp"

#include <cmath>

namespace dlmfsi {

namespace {

// a + b = s + e exactly (Knuth's two-sum).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  double bv = s - a;
  double av = s - bv;
  e = (a - av) + (b - bv);
}

// Adds q to the non-overlapping expansion h[0..n) (increasing magnitude); returns the new length.
// Shewchuk's GROW-EXPANSION with zero elimination: the result is again non-overlapping and exact.
int grow_expansion(double* h, int n, double q) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    double s, e;
    two_sum(q, h[i], s, e);
    q = s;
    if (e != 0) h[m++] = e;
  }
  if (q != 0) h[m++] = q;
  return m;
}

}  // namespace

int orient2d_exact(Point a, Point b, Point c) {
  // Six products, each split exactly into p + e with a fused multiply-add.
  const double f[6][2] = {{a.x, b.y}, {-a.y, b.x}, {b.x, c.y}, {-b.y, c.x}, {c.x, a.y}, {-c.y, a.x}};
  double h[12];
  int n = 0;
  for (const auto& t : f) {
    double p = t[0] * t[1];
    double e = std::fma(t[0], t[1], -p);
    n = grow_expansion(h, n, p);
    n = grow_expansion(h, n, e);
  }
  // In a non-overlapping expansion the last (largest) component carries the sign.
  if (n == 0) return 0;
  return h[n - 1] > 0 ? 1 : -1;
}

}  // namespace dlmfsi
