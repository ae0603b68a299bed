// The moments piece integrator: both bases fitted of degree <= 1, the map affine on the triangle. On the
// piece P (area A, centroid c, central second moments M = int_P (y - c)(y - c)^T dy) every product of two
// affine functions f g integrates exactly as
//   int_P f g dy = A f(c) g(c) + grad f . M grad g,
// and a product of gradients is constant. With y = X(s), ds = dy / det dX/ds and psi's gradient in y,
// (dX/ds)^-T grad_s psi, the block gets
//   (c2 / det) [A phi_j(c) psi_i(c) + grad phi_j . M grad_y psi_i] + c1 (A / det) grad_s psi_i . (grad phi_j dX/ds).
// A, c and M come from the piece's fan; no quadrature point.
#pragma once
#include "integration/integrator.hpp"

namespace dlmfsi {

class MomentIntegrator : public PieceIntegrator {
 public:
  // At most this many fitted functions per side (the per-function sums live on the stack).
  static constexpr int kMaxFunctions = 48;
  // Can it integrate these bases (on affine images)?
  static bool applies(const Integrand& integrand);

  MomentIntegrator(const Integrand& integrand, CouplingReport& counts);
  // The multiplier's terms on the image's (affine) triangle: its gradients in s and in y, and c2 / det.
  void start(const ClippedImage& image) override;
  double integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) override;

 private:
  struct Moments;
  // The block's part once the moments are known; FW and SW the numbers of fitted functions when fixed at
  // compile time (P1 x P1: 3 and 3), 0 for any.
  template <int FW, int SW>
  void add(const ClippedImage& image, int kf, const Moments& moments, LocalBlock& block);

  const Integrand& integrand_;
  CouplingReport& counts_;
  bool gradients_;  // c1 != 0
  int fluid_functions_, multiplier_functions_;
  // One pair that reads every fitted function in order (a scalar space on each side).
  bool one_pair_;
  void (MomentIntegrator::*add_)(const ClippedImage&, int, const Moments&, LocalBlock&);
  // start()'s terms, the same for every piece of the triangle: c2 / det, and per multiplier function its
  // gradient in s (sgx, sgy) and in y, (dX/ds)^-T grad_s psi (syx, syy).
  double mass_ = 0;
  double sgx_[kMaxFunctions], sgy_[kMaxFunctions], syx_[kMaxFunctions], syy_[kMaxFunctions];
};

}  // namespace dlmfsi
