// The point-by-point piece integrator: any basis (fitted or evaluated through the element itself) and
// either gradient product. On each triangle t = (y_0, y_t, y_t+1) of the piece's fan, a rule of degree
// image.degree with points q in fluid coordinates,
//   block_ij += sum_q |t| w_q f_ij(xi_q) / det dX/ds(xi_q),   xi_q = X^-1(y_q),
// xi_q by Newton's method started from the interpolation of the corners' pull-backs. At each point
//   f_ij = c2 psi_i . phi_j + c1 grad psi_i : G_j,
// chain rule: G_j = grad phi_j dX/ds, i.e. sum_b d_b psi_i (sum_a d_a phi_j dX_a/ds_b) per component pair;
// listings' product (needs two pairs, the pair index being the vector component):
//   grad psi : G = sum_{a,b} d_b psi^(a) sum_c dX_a/ds_c d_b phi^(c).
#pragma once
#include <vector>

#include "integration/integrator.hpp"

namespace dlmfsi {

class PointIntegrator : public PieceIntegrator {
 public:
  PointIntegrator(const Integrand& integrand, CouplingReport& counts);
  double integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) override;

  // block += ds f_ij at one point: y in fluid element kf (entered in the block), xi its reference point in
  // solid triangle ks, jac = dX/ds there. The quadrature method adds its points through this.
  void add_point(int kf, Point y, int ks, Point xi, double ds, const double jac[2][2], LocalBlock& block) {
    add_reference_point(kf, integrand_.fluid.to_reference(kf, y), ks, xi, ds, jac, block);
  }
  // The same with y given relative to origin (y_local = y - origin), fluid element kf's corners translated by
  // -origin as the caller's geometry did (AffineElementMaps::to_reference).
  void add_point(int kf, Point y_local, Point origin, int ks, Point xi, double ds, const double jac[2][2],
                 LocalBlock& block) {
    add_reference_point(kf, integrand_.fluid.to_reference(kf, y_local, origin), ks, xi, ds, jac, block);
  }

 private:
  // The same with eta, y's reference point in fluid element kf.
  void add_reference_point(int kf, Point eta, int ks, Point xi, double ds, const double jac[2][2], LocalBlock& block);

  const Integrand& integrand_;
  CouplingReport& counts_;
  // Both bases at the point, in Basis::evaluate's layout
  std::vector<double> fluid_values_, multiplier_values_;
};

}  // namespace dlmfsi
