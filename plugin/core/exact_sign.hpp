// The exact sign of a sum of products of doubles: the arithmetic under the exact predicates.
#pragma once

namespace dlmfsi {

// Sign of sum_k prod_{i < arity} f[k * arity + i] for any finite doubles (arity 2 or 3, count <= 32),
// exactly. Each product is split into a non-overlapping expansion with fused multiply-adds and summed
// exactly while every rounding error is itself a double (no underflow, no overflow); when a product
// leaves that range (coordinates below about 1e-146 or above 1e146 for arity 2, 1e-100 / 1e100 for
// arity 3, subnormals), the sign is found in integer arithmetic instead. Returns 0 when a factor is not
// finite (outside the contract; nothing undefined happens).
int exact_sign_of_sum(const double* f, int count, int arity);

// The same sum's value: the exact sum rounded, with a relative error of a few units in the last place
// (sign exact, 0 exactly when the sum is 0). For constructions whose floating-point evaluation cancels.
double exact_sum(const double* f, int count, int arity);

}  // namespace dlmfsi
