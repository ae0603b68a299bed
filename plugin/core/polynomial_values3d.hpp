// Many polynomials on one tetrahedron evaluated at many points, with their physical gradients: the inner
// loop of the 3D bases' evaluation (polynomial_basis3d.hpp).
#pragma once
#include <cstddef>

#include "point3.hpp"

namespace dlmfsi {

// The width polynomials of degree (0 to kMaxLatticeDegree) with monomial coefficients coef (lattice3d.hpp
// order, monomial_count3(degree) each) at the n reference points xi: value[f * n + p] and, when gradient is
// not null, the physical first derivatives gradient[(3 f + i) * n + p] through j = d xi / d x (row-major).
// When twin is not null, polynomial f with twin[f] >= 0 is a copy of polynomial twin[f] < f (its values
// are copied, not computed).
void evaluate_polynomials3(int degree, const double* coef, size_t width, const int* twin, const double* j,
                           const Point3* xi, int n, double* value, double* gradient);

}  // namespace dlmfsi
