#include "geometry/exact_sign.hpp"

#include <climits>
#include <cmath>
#include <cstdint>

namespace dlmfsi {

namespace {

// a + b = s + e exactly (Knuth's two-sum).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
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

// The factor x as m 2^e with m an integer, |m| < 2^53 (exact, subnormals included).
inline std::int64_t mantissa(double x, int& e) {
  int ex;
  const double f = std::frexp(x, &ex);
  e = ex - 53;
  return static_cast<std::int64_t>(std::ldexp(f, 53));
}

// The integer path: each product is an integer of at most 3 * 53 bits times 2^E; the positive and the
// negative terms are added, shifted to the smallest E, into two wide unsigned accumulators, which are
// then compared, and the difference's leading 128 bits rounded to a double, returned as m 2^exponent
// (frexp's m: the value itself may lie far below the doubles). Exponents of products of three doubles span
// less than 6300 bits: 104 limbs of 64 bits hold every sum of up to 32 terms.
double integer_sum(const double* f, int count, int arity, int& sign, int& exponent) {
  sign = 0;
  exponent = 0;
  constexpr int kLimbs = 104;
  struct Term {
    bool negative;
    std::uint64_t m[3];  // little-endian limbs of |product of mantissas|
    int e;
  };
  Term terms[32];
  int n = 0, emin = INT_MAX;
  for (int k = 0; k < count && n < 32; ++k) {
    Term t{false, {1, 0, 0}, 0};
    bool zero = false;
    for (int i = 0; i < arity; ++i) {
      const double x = f[k * arity + i];
      if (x == 0) zero = true;
      int e;
      const std::int64_t m = mantissa(x, e);
      t.negative = t.negative != (m < 0);
      t.e += e;
      // t.m *= |m|
      const auto a = static_cast<std::uint64_t>(m < 0 ? -m : m);
      __extension__ typedef unsigned __int128 U128;
      U128 carry = 0;
      for (auto& limb : t.m) {
        const U128 p = static_cast<U128>(limb) * a + carry;
        limb = static_cast<std::uint64_t>(p);
        carry = p >> 64;
      }
    }
    if (zero) continue;
    terms[n++] = t;
    if (t.e < emin) emin = t.e;
  }
  if (n == 0) return 0;
  std::uint64_t pos[kLimbs] = {}, neg[kLimbs] = {};
  for (int k = 0; k < n; ++k) {
    std::uint64_t* acc = terms[k].negative ? neg : pos;
    const int shift = terms[k].e - emin, w = shift / 64, b = shift % 64;
    // the term shifted left by shift bits: limbs w .. w + 3
    std::uint64_t add[4];
    const std::uint64_t* m = terms[k].m;
    add[0] = m[0] << b;
    add[1] = b ? (m[1] << b) | (m[0] >> (64 - b)) : m[1];
    add[2] = b ? (m[2] << b) | (m[1] >> (64 - b)) : m[2];
    add[3] = b ? m[2] >> (64 - b) : 0;
    std::uint64_t carry = 0;
    for (int i = w; i < kLimbs && (i < w + 4 || carry); ++i) {
      const std::uint64_t v = i < w + 4 ? add[i - w] : 0;
      const std::uint64_t s = acc[i] + v;
      const std::uint64_t c1 = s < v ? 1 : 0;
      acc[i] = s + carry;
      carry = c1 | (acc[i] < s ? 1 : 0);
    }
  }
  int top = kLimbs - 1;
  while (top >= 0 && pos[top] == neg[top]) --top;
  if (top < 0) return 0;
  const bool negative = neg[top] > pos[top];
  sign = negative ? -1 : 1;  // exact, even where the value below underflows
  const std::uint64_t* big = negative ? neg : pos;
  const std::uint64_t* small = negative ? pos : neg;
  // big - small, limbs 0 .. top; the leading non-zero limbs give the value
  std::uint64_t diff[kLimbs];
  std::uint64_t borrow = 0;
  for (int i = 0; i <= top; ++i) {
    const std::uint64_t d = big[i] - small[i];
    const std::uint64_t b1 = big[i] < small[i] ? 1 : 0;
    diff[i] = d - borrow;
    borrow = b1 | (d < borrow ? 1 : 0);
  }
  while (top > 0 && diff[top] == 0) --top;
  double v = static_cast<double>(diff[top]);
  if (top > 0) v += std::ldexp(static_cast<double>(diff[top - 1]), -64);
  // (the limbs below move the value by less than 2^-64 relative)
  int k;
  const double m = std::frexp(v, &k);
  exponent = 64 * top + emin + k;
  return negative ? -m : m;
}

// The exact sum as a non-overlapping expansion h[0..n) (increasing magnitude); false when a product
// leaves the range where the expansion is exact (the integer path must decide).
bool expansion(const double* f, int count, int arity, double* h, int& n) {
  // The floating-point expansion is exact when the rounding error of every partial product is a double
  // and nothing overflows: with |x| < 2^ex, the error of x y is a multiple of 2^(ex + ey - 106), that of
  // (x y) z (both parts) a multiple of 2^(ex + ey + ez - 159); both at least 2^-1074, and the products
  // below 2^1000.
  for (int k = 0; k < count; ++k) {
    int total = 0;
    bool zero = false;
    for (int i = 0; i < arity; ++i) {
      const double x = f[k * arity + i];
      if (x == 0) zero = true;
      int e;
      std::frexp(x, &e);
      total += e;
      const int floor = i == 1 ? -968 : -915;
      if (!zero && i >= 1 && (total < floor || total > 1000)) return false;
    }
  }
  n = 0;
  for (int k = 0; k < count; ++k) {
    const double* x = f + k * arity;
    const double p = x[0] * x[1];
    if (p == 0) continue;  // a zero factor (no underflow in range)
    const double e = std::fma(x[0], x[1], -p);
    if (arity == 2) {
      n = grow_expansion(h, n, p);
      if (e != 0) n = grow_expansion(h, n, e);
      continue;
    }
    const double z = x[2];
    if (z == 0) continue;
    const double pz = p * z;
    n = grow_expansion(h, n, pz);
    const double pe = std::fma(p, z, -pz);
    if (pe != 0) n = grow_expansion(h, n, pe);
    if (e != 0) {
      const double ez = e * z;
      n = grow_expansion(h, n, ez);
      const double ee = std::fma(e, z, -ez);
      if (ee != 0) n = grow_expansion(h, n, ee);
    }
  }
  return true;
}

bool all_finite(const double* f, int count, int arity) {
  for (int k = 0; k < count * arity; ++k)
    if (!std::isfinite(f[k])) return false;
  return true;
}

}  // namespace

int exact_sign_of_sum(const double* f, int count, int arity) {
  if (!all_finite(f, count, arity)) return 0;
  double h[4 * 32];
  int n;
  if (!expansion(f, count, arity, h, n)) {
    int sign, exponent;
    integer_sum(f, count, arity, sign, exponent);
    return sign;
  }
  // In a non-overlapping expansion the last (largest) component carries the sign.
  if (n == 0) return 0;
  return h[n - 1] > 0 ? 1 : -1;
}

double exact_sum(const double* f, int count, int arity, int& exponent) {
  exponent = 0;
  if (!all_finite(f, count, arity)) return 0;
  double h[4 * 32];
  int n;
  if (!expansion(f, count, arity, h, n)) {
    int sign;
    return integer_sum(f, count, arity, sign, exponent);
  }
  // Adding the components from the smallest: each is below half an ulp of the next, so the sum is the
  // exact one to within a few ulps. On this path every component is a multiple of 2^-1074 (expansion's
  // floors), so a sum below 2^-1022 is a subnormal double exactly: nothing is lost to underflow.
  double s = 0;
  for (int i = 0; i < n; ++i) s += h[i];
  return std::frexp(s, &exponent);
}

}  // namespace dlmfsi
