// Does a polynomial map fold a tetrahedron? Its jacobian determinant is certified positive on the whole
// reference tetrahedron, not only at sample points (the counterpart of fold.hpp).
//
// For a map of degree d, det dX/dxi is a polynomial of degree n = 3(d - 1) in the reference coordinates
// (P2 maps: 3, P1b maps: 9). Written in the Bernstein basis of degree n on a sub-tetrahedron,
//   det = sum_m b_m B_m,  B_m = n! / (m0! m1! m2! m3!) l0^m0 l1^m1 l2^m2 l3^m3 >= 0,  sum_m B_m = 1,
// (l the sub-tetrahedron's barycentric coordinates), its values there lie between the smallest and the
// largest b_m. The b_m come from the values at the sub-tetrahedron's degree-n lattice, b = C^-1 v with
// C[p][m] = B_m(lattice point p); the exact b_m are within kappa (max_p e_p + r) of the computed ones, where
// kappa = max_m sum_p |C^-1[m][p]|, e_p bounds the round-off of the value v_p and r that of the computed
// inverse (the residual max_p |v_p - (C b)_p| plus its own round-off; fold3d.cpp). On each sub-tetrahedron:
//  - every computed b_m > 2 kappa (max_p e_p + r): det > 0 there (certified);
//  - a value v_p <= 0 at a lattice point: the map folds or flattens there (the corners are lattice points);
//  - otherwise split it into 8 (red refinement; the b_m converge to the values as h^2) and test the parts,
//    down to max_depth levels and at most max_tetrahedra tested in all; what is left undecided has det
//    within about 4^-max_depth of zero relative to its scale, and is reported as a (near) fold.
#pragma once
#include <functional>

#include "map/element_map3d.hpp"
#include "map/fold.hpp"
#include "point3.hpp"

namespace dlmfsi {

// The jacobian determinant at a reference point and a bound on its round-off.
struct DetSample {
  double value;
  double round_off;
};

// det(xi): a polynomial of degree n (0 <= n <= kMaxJacobianDegree3) in xi. where: a reference point at which
// det <= 0 (Folds) or the centroid of an undecided sub-tetrahedron (NearlyFolds). tested: the number of
// sub-tetrahedra tested (1 when the whole tetrahedron is certified at once).
constexpr int kMaxJacobianDegree3 = 15;
JacobianSign jacobian_sign3(const std::function<DetSample(Point3)>& det, int n, int max_depth, int max_tetrahedra,
                            Point3& where, int* tested = nullptr);

// kappa for degree n (above): how much the conversion from lattice values to Bernstein coefficients can
// amplify the values' round-off.
double bernstein_amplification3(int n);

// The certification's limits: 10 levels of red refinement (det within about 4^-10 of zero, relative, is a
// near fold) and 4096 sub-tetrahedra tested per solid tetrahedron.
constexpr int kFoldDepth = 10;
constexpr int kFoldTetrahedra = 4096;

// det dX/dxi of the fitted polynomial of map at xi (mt.fitted_degree() >= 1) and a bound on its round-off.
DetSample jacobian_det(const TetrahedronMap& mt, Point3 xi);

// Throws Error naming the tetrahedron when det dX/dxi is not positive somewhere on it ("folds": at a
// reference point given in the message) or comes within the limits above of zero ("nearly folds").
void check_fold(const TetrahedronMap& mt);

}  // namespace dlmfsi
