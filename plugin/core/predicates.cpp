#include "predicates.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

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

// Sign of sum_k x_k * y_k for any finite doubles, in integer arithmetic: each product is an integer
// m_k < 2^106 times 2^e_k (the 53-bit integer mantissas multiplied), and the terms are added in a
// two's-complement integer wide enough for every exponent a product of doubles can have. Slow; used only
// when a product leaves the range where the floating-point expansion is exact (the rounding error of
// each product must be a double, |x y| >= 2^-968, and no partial sum may overflow).
__extension__ typedef unsigned __int128 Uint128;

int sign_of_sum_of_products(const double (*f)[2], int count) {
  struct Term {
    bool negative;
    Uint128 m;
    int e;
  };
  Term terms[8];
  int n = 0, emin = INT_MAX;
  for (int k = 0; k < count && n < 8; ++k) {
    const double x = f[k][0], y = f[k][1];
    if (!std::isfinite(x) || !std::isfinite(y)) return 0;  // outside the contract; no undefined conversion
    if (x == 0 || y == 0) continue;
    int ex, ey;
    // x = mx 2^(ex - 53) with |mx| < 2^53 an integer (exact, subnormals included)
    const auto mx = static_cast<std::int64_t>(std::ldexp(std::frexp(x, &ex), 53));
    const auto my = static_cast<std::int64_t>(std::ldexp(std::frexp(y, &ey), 53));
    Term& t = terms[n++];
    t.negative = (mx < 0) != (my < 0);
    t.m = static_cast<Uint128>(mx < 0 ? -mx : mx) * static_cast<Uint128>(my < 0 ? -my : my);
    t.e = ex + ey - 106;
    emin = std::min(emin, t.e);
  }
  if (n == 0) return 0;
  // frexp exponents lie in [-1073, 1024], so e - emin < 4200 bits; with 106 bits of mantissa and carries
  // 70 limbs of 64 bits suffice.
  constexpr int kLimbs = 70;
  std::uint64_t acc[kLimbs] = {};
  for (int k = 0; k < n; ++k) {
    const int shift = terms[k].e - emin;
    std::uint64_t add[kLimbs] = {};
    const int w = shift / 64, b = shift % 64;
    const auto lo = static_cast<std::uint64_t>(terms[k].m), hi = static_cast<std::uint64_t>(terms[k].m >> 64);
    add[w] = lo << b;
    add[w + 1] = b ? (hi << b) | (lo >> (64 - b)) : hi;
    add[w + 2] = b ? hi >> (64 - b) : 0;
    if (terms[k].negative) {  // two's complement negation
      bool carry = true;
      for (auto& v : add) {
        v = ~v + (carry ? 1 : 0);
        carry = carry && v == 0;
      }
    }
    std::uint64_t carry = 0;
    for (int i = 0; i < kLimbs; ++i) {
      const std::uint64_t s = acc[i] + add[i];
      const std::uint64_t c1 = s < acc[i] ? 1 : 0;
      acc[i] = s + carry;
      carry = c1 | (acc[i] < s ? 1 : 0);
    }
  }
  if (acc[kLimbs - 1] >> 63) return -1;
  for (auto v : acc)
    if (v) return 1;
  return 0;
}

// Sign of sum_k x_k * y_k (count <= 8) for any finite doubles: each product split exactly into p + e with
// a fused multiply-add and summed into a non-overlapping expansion, exact while every product's rounding
// error is a double and nothing overflows; outside 2^-968 <= |x y| <= 2^1018 (a coordinate below about
// 1e-146 or above 1e146, subnormals included, next to others) the sign is found with integers instead.
int sign_of_products(const double (*f)[2], int count) {
  for (int k = 0; k < count; ++k) {
    const double p = std::fabs(f[k][0] * f[k][1]);
    if (f[k][0] != 0 && f[k][1] != 0 && !(p >= 0x1p-968 && p <= 0x1p+1018)) return sign_of_sum_of_products(f, count);
  }
  double h[16];
  int n = 0;
  for (int k = 0; k < count; ++k) {
    const double p = f[k][0] * f[k][1];
    const double e = std::fma(f[k][0], f[k][1], -p);
    n = grow_expansion(h, n, p);
    n = grow_expansion(h, n, e);
  }
  // In a non-overlapping expansion the last (largest) component carries the sign.
  if (n == 0) return 0;
  return h[n - 1] > 0 ? 1 : -1;
}

}  // namespace

int orient2d_exact(Point a, Point b, Point c) {
  const double f[6][2] = {{a.x, b.y}, {-a.y, b.x}, {b.x, c.y}, {-b.y, c.x}, {c.x, a.y}, {-c.y, a.x}};
  return sign_of_products(f, 6);
}

int cross_sign_exact(Point p, Point q, Point r, Point s) {
  // (q - p) x (s - r) = qx sy - qx ry - px sy + px ry - qy sx + qy rx + py sx - py rx
  const double f[8][2] = {{q.x, s.y}, {-q.x, r.y}, {-p.x, s.y}, {p.x, r.y},
                          {-q.y, s.x}, {q.y, r.x}, {p.y, s.x}, {-p.y, r.x}};
  return sign_of_products(f, 8);
}

}  // namespace dlmfsi
