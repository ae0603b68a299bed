// A basis's fitted functions evaluated at many points of one element at once, the monomials formed once per
// point.
#pragma once
#include "fe/basis_fit.hpp"

namespace dlmfsi {

// The functions of fit (fitted() only) at the n reference points xi of element k: value[f * n + p] for the
// f-th of fit.functions() at point p, and when dx and dy are not null the physical first derivatives in
// the same layout, through inverse_jacobian = d xi / d x on element k (AffineElementMaps).
void evaluate_at_points(const BasisFit& fit, int k, const double* inverse_jacobian, const Point* xi, int n,
                        double* value, double* dx, double* dy);

}  // namespace dlmfsi
