// The monomial-moments piece integrator for tetrahedra: a fitted fluid basis of degree >= 2 (P1b, P2, ...),
// a fitted multiplier of degree <= 1, the map affine on the tetrahedron, the chain rule (or c1 = 0). The
// piece's moments M_m = int_P eta^m dy of the monomials of degree <= d + 1 in the fluid element's reference
// coordinates eta (d the fluid degree; by the rule of degree d + 1 on the piece's tetrahedra, exact) carry
// every integral: a fluid function phi = sum_m c_m eta^m and an affine multiplier function
// psi = psi(c) + q . (eta - eta_c) (c the piece's centroid, eta_c its reference coordinates, q_k = grad_y psi
// . e_k with e_k the fluid element's edges) give
//   int_P psi phi dy = psi(c) A + q . (B - eta_c A),  A = sum_m c_m M_m,  B_k = sum_m c_m M_(m eta_k),
//   int_P grad_y phi dy = (d eta / d y)^T sum_m c_m grad_eta(eta^m) integrated (the M_m of degree d - 1),
// and with ds = dy / det dX/ds the block gets
//   (c2 / det) int_P psi_i phi_j dy + (c1 / det) grad_s psi_i . (dX/ds^T int_P grad_y phi_j dy).
// The points only form the moments: the bases are never evaluated at them. On fluid elements without the
// shared fit, the point-by-point integrator.
#pragma once
#include <vector>

#include "integration/integrate_points3d.hpp"
#include "integration/integrator3d.hpp"

namespace dlmfsi {

class MonomialIntegrator3 : public PieceIntegrator3 {
 public:
  // Can it integrate these bases (on affine images)?
  static bool applies(const Integrand3& integrand);

  MonomialIntegrator3(const Integrand3& integrand, CouplingReport& counts);
  double integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) override;

 private:
  const Integrand3& integrand_;
  CouplingReport& counts_;
  PointIntegrator3 points_;  // for fluid elements with their own fits
  int fluid_functions_, multiplier_functions_;
  // Per piece: the rule's points (eta) and weights (dy), the moments, and per function the sums.
  std::vector<Point3> eta_;
  std::vector<double> weight_, moment_, first_, gradient_sum_, value_, gradient_, q_;
};

}  // namespace dlmfsi
