// The exact sign of a sum of products of doubles: the arithmetic under the exact predicates.
#pragma once

namespace dlmfsi {

// d = a - b rounded; true when that subtraction is exact. TwoSum(a, -b) with s = d: its error term
// (a - (s + b)) - (b + (s - (s + b))) is 0 iff s = a - b exactly.
inline bool exact_difference(double a, double b, double& d) {
  d = a - b;
  const double back = d + b;
  return (a - back) - (b + (d - back)) == 0;
}

// Sign of sum_k prod_{i < arity} f[k * arity + i] for any finite doubles (arity 2 or 3, count <= 32),
// exactly. Each product is split into a non-overlapping expansion with fused multiply-adds and summed
// exactly while every rounding error is itself a double (no underflow, no overflow); when a product
// leaves that range (coordinates below about 1e-146 or above 1e146 for arity 2, 1e-100 / 1e100 for
// arity 3, subnormals), the sign is found in integer arithmetic instead. Returns 0 when a factor is not
// finite (outside the contract; nothing undefined happens).
int exact_sign_of_sum(const double* f, int count, int arity);

// The same sum's value as m 2^e (e in exponent; m = 0 when the sum is 0, else 0.5 <= |m| < 1, as frexp
// gives): the exact sum rounded, with a relative error of a few units in the last place, however far below
// the doubles it lies (sums of products of subnormal or tiny differences). For constructions whose
// floating-point evaluation cancels: a ratio of two such sums.
double exact_sum(const double* f, int count, int arity, int& exponent);

}  // namespace dlmfsi
