// The moments piece integrator for tetrahedra: both bases fitted of degree <= 1, the map affine on the
// tetrahedron, the chain rule (or c1 = 0). On the piece P (volume V, centroid c, central second moments
// M = int_P (y - c)(y - c)^T dy) a product of two affine functions integrates as
//   int_P f g dy = V f(c) g(c) + grad f . M grad g,
// and a product of gradients is constant. With y = X(s), ds = dy / det dX/ds and psi's gradient in y
// (dX/ds)^-T grad_s psi, the block gets
//   (c2 / det) [V phi_j(c) psi_i(c) + grad phi_j . M grad_y psi_i] + c1 (V / det) grad_s psi_i . (dX/ds^T grad phi_j).
#pragma once
#include "integration/integrator3d.hpp"

namespace dlmfsi {

class MomentIntegrator3 : public PieceIntegrator3 {
 public:
  // At most this many fitted functions per side (the per-function sums live on the stack).
  static constexpr int kMaxFunctions = 64;
  // Can it integrate these bases (on affine images)?
  static bool applies(const Integrand3& integrand);

  MomentIntegrator3(const Integrand3& integrand, CouplingReport& counts);
  // The image's (affine) tetrahedron's terms, SolidTerms.
  void start(const ClippedImage3& image) override;
  double integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) override;

 private:
  // What a piece's block takes from its solid tetrahedron alone, formed by start(): c2 / det and each
  // multiplier function's gradient in s and in y, J^-T grad_s psi (constant on the tetrahedron: degree <= 1).
  struct SolidTerms {
    double mass = 0;
    double gradient_s[3 * kMaxFunctions], gradient_y[3 * kMaxFunctions];
  };

  // The scalar P1 x P1 mass (one pair of four functions each, in order, c1 = 0): the block's terms in loops of
  // fixed length, the same sums in the same order as the general loops of integrate (bit for bit).
  double add_scalar_p1_mass(double volume, const double (&m)[3][3], double scale, const double* fv, const double* fg,
                            const double* sv, LocalBlock& block);

  const Integrand3& integrand_;
  CouplingReport& counts_;
  int fluid_functions_, multiplier_functions_;
  bool scalar_p1_mass_ = false;
  SolidTerms solid_terms_;
};

}  // namespace dlmfsi
