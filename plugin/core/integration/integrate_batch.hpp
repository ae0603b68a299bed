// The batch piece integrator: both bases fitted (PolynomialBasis), the chain rule (or c1 = 0). The rule's
// points on the piece's fan are gathered with their reference coordinates in the fluid element (eta, affine
// in y: interpolated from the piece's corners) and in the solid triangle (xi: interpolated too where the
// map is affine; otherwise Newton's pull-back, started from the interpolation of the corners' pull-backs),
// and every entry of the block gets
//   block_ij += sum_q w_q [c2 psi_i phi_j + c1 grad psi_i . (grad phi_j dX/ds)],  w_q = |t| weight_q / det dX/ds.
// Where c1 = 0 or the multiplier's gradients are constant on the solid triangle (fitted at degree 0 or 1),
// the sums go through the fluid fit's monomials m_k(eta) = eta1^a eta2^b: with phi_j = sum_k C_jk m_k and
// its reference derivatives d_e phi_j = sum_k E_ejk m_k,
//   sum_q w_q psi_i phi_j = sum_k C_jk P_ik,       P_ik = sum_q w_q psi_i(q) m_k(q),
//   sum_q w_q grad phi_j dX/ds = sum_e,k E_ejk Q_ek,  Q_ek = sum_q w_q (d eta_e / dy  dX/ds)(q) m_k(q),
// so the points carry one product per monomial and multiplier function, and the fluid functions are never
// evaluated at them. Otherwise each basis is evaluated on all points at once and every entry gets one
// weighted sum along them. A component pair that repeats an earlier pair's functions (ComponentPair::source)
// copies its sums on elements of the shared fits.
#pragma once
#include <array>
#include <vector>

#include "integration/integrator.hpp"
#include "fe/rules.hpp"

namespace dlmfsi {

class BatchIntegrator : public PieceIntegrator {
 public:
  BatchIntegrator(const Integrand& integrand, CouplingReport& counts);
  double integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) override;
  // The same sums over n given points of the (not affine) solid triangle mt in fluid element kf (entered in
  // the block): y the points relative to origin (y - origin, kf's corners translated by -origin as the
  // caller's geometry did), xi their reference points in mt, weight their weights (ds), jacobian dX/ds there
  // as (jac[0][0], jac[0][1], jac[1][0], jac[1][1]). The curved method's rules come through this.
  void integrate_points(const MappedTriangle& mt, int kf, size_t n, const Point* y, Point origin, const Point* xi,
                        const double* weight, const std::array<double, 4>* jacobian, LocalBlock& block);

 private:
  // The rule's points on the piece's fan: weight_, eta_, xi_, jacobian_; returns their number n.
  size_t gather(const ClippedImage& image, int kf, const Piece& piece);
  // Room for n points in the per-point arrays.
  void reserve(size_t n);
  // The sums over the n gathered points, added to the block.
  void add_gathered(const MappedTriangle& mt, int kf, size_t n, LocalBlock& block);
  // Not by moments: both bases at the n points, the fluid functions' values and chain-rule gradients
  // weighted (twins: only those of pairs that are not copies).
  void evaluate(const MappedTriangle& mt, int kf, size_t n, bool twins);
  // By moments: P and Q along the n points, the multiplier's constant gradients (at the first point) and,
  // from Q, each fluid function's sum_q c1 w_q grad phi_j dX/ds (gradient_sums_).
  void moments(const MappedTriangle& mt, int kf, size_t n, bool twins);
  // block_ij += the sums, for every pair (fluid element kf: its fit's coefficients C).
  void add_sums(int kf, size_t n, bool twins, LocalBlock& block);

  const Integrand& integrand_;
  CouplingReport& counts_;
  const std::vector<RulePoint>& affine_rule_;  // exact for the product of the bases
  bool gradients_;                              // c1 != 0
  // c1 != 0 and a multiplier fitted at degree 0 or 1: its gradients are constant on each solid triangle,
  // evaluated once (constant_gradients_: d/dx, d/dy of each function, then values unused) and dotted with
  // each fluid function's weighted gradient sum (gradient_sums_: x, y per function).
  bool constant_multiplier_gradients_;
  bool by_moments_;           // c1 = 0 or constant multiplier gradients: the sums through the monomials
  int fluid_terms_;           // the fluid fit's monomials (PolynomialBasis::terms: degree d), and
  int fluid_gradient_terms_;  // those of degree d - 1 (its derivatives')
  size_t fluid_functions_, multiplier_functions_;
  // Per gathered point: weight, reference points in the fluid element and the solid triangle, dX/ds
  // (non-affine maps); then both bases' values and gradients, function by function along the points.
  std::vector<double> weight_;
  std::vector<Point> eta_, xi_, y_;  // y_: the points (non-affine maps)
  std::vector<std::array<double, 4>> jacobian_;
  std::vector<double> pull_back_scratch_;
  std::vector<double> fluid_values_, multiplier_values_;
  std::vector<double> constant_gradients_, gradient_sums_;
  // By moments: the fluid monomials at the points (point-major), a weight row per point, P (per multiplier
  // function, fluid_terms_ each), the per-point c1 w_q d eta_e/dy dX/ds_c (frame_, four rows) and Q (the
  // four (e, c) rows of fluid_gradient_terms_ moments)
  std::vector<double> monomials_, row_, value_moments_, frame_, gradient_moments_;
};

}  // namespace dlmfsi
