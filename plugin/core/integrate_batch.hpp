// The batch piece integrator: both bases fitted (PolynomialBasis), the chain rule (or c1 = 0). The rule's
// points on the piece's fan are gathered with their reference coordinates in the fluid element (eta, affine
// in y: interpolated from the piece's corners) and in the solid triangle (xi: interpolated too where the
// map is affine; otherwise Newton's pull-back, started from the interpolation of the corners' pull-backs),
// each basis is evaluated on all points at once, and every entry of the block gets one weighted sum,
//   block_ij += sum_q w_q [c2 psi_i phi_j + c1 grad psi_i . (grad phi_j dX/ds)],  w_q = |t| weight_q / det dX/ds,
// with the weights and the jacobian folded into the fluid functions first. A component pair that repeats an
// earlier pair's functions (ComponentPair::source) copies its sums on elements of the shared fits.
#pragma once
#include <array>
#include <vector>

#include "integrator.hpp"
#include "rules.hpp"

namespace dlmfsi {

class BatchIntegrator : public PieceIntegrator {
 public:
  BatchIntegrator(const Integrand& integrand, CouplingReport& counts);
  void integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) override;

 private:
  // The rule's points on the piece's fan: weight_, eta_, xi_, jacobian_; returns their number n.
  size_t gather(const ClippedImage& image, int kf, const Piece& piece);
  // Both bases at the n points, the fluid functions' values and chain-rule gradients weighted (twins: only
  // those of pairs that are not copies).
  void evaluate(const MappedTriangle& mt, int kf, size_t n, bool twins);
  // block_ij += the sums along the points, for every pair.
  void add_sums(size_t n, bool twins, LocalBlock& block);

  const Integrand& integrand_;
  CouplingReport& counts_;
  const std::vector<RulePoint>& affine_rule_;  // exact for the product of the bases
  bool gradients_;                              // c1 != 0
  // c1 != 0 and a multiplier fitted at degree 0 or 1: its gradients are constant on each solid triangle,
  // evaluated once (constant_gradients_: d/dx, d/dy of each function, then values unused), and evaluate
  // sums each fluid function's weighted gradients along the points (gradient_sums_: x, y per function).
  bool constant_multiplier_gradients_;
  size_t fluid_functions_, multiplier_functions_;
  // Per gathered point: weight, reference points in the fluid element and the solid triangle, dX/ds
  // (non-affine maps); then both bases' values and gradients, function by function along the points.
  std::vector<double> weight_;
  std::vector<Point> eta_, xi_, y_;  // y_: the points (non-affine maps)
  std::vector<std::array<double, 4>> jacobian_;
  std::vector<double> pull_back_scratch_;
  std::vector<double> fluid_values_, multiplier_values_;
  std::vector<double> constant_gradients_, gradient_sums_;
};

}  // namespace dlmfsi
