// The real roots of a polynomial of one variable in a closed interval, for the crossings of a curved image's
// edges with straight lines.
#pragma once

namespace dlmfsi {

constexpr int kMaxRootsDegree = 8;

// p(t) = sum_k c[k] t^k, degree <= kMaxRootsDegree, evaluated by Horner's rule.
double polynomial_value(const double* c, int degree, double t);

// The roots of p in [lo, hi] where p changes sign, in increasing order, into roots (room for degree of
// them); returns their number. p_lo and p_hi are p's values at the ends as the caller knows them (so that
// two curves meeting at a common end see the same sign there): an end where p is 0 counts as a root. The
// interval is cut at the roots of p' (found the same way); on each monotone part a sign change is found by
// Newton's steps kept inside the bracket, to the last bits. A root of even multiplicity (a tangency) is no sign change and is left out; the zero
// polynomial has none.
int roots_in(const double* c, int degree, double lo, double hi, double p_lo, double p_hi, double* roots);

}  // namespace dlmfsi
