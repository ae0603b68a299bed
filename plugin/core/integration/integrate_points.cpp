#include "integration/integrate_points.hpp"

#include <string>

#include "sides/report.hpp"
#include "sides/sides.hpp"
#include "errors.hpp"
#include "fe/rules.hpp"

namespace dlmfsi {

PointIntegrator::PointIntegrator(const Integrand& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts),
      fluid_values_(static_cast<size_t>(integrand.fluid_space.local_dofs()) * integrand.fluid_space.components() * 3),
      multiplier_values_(static_cast<size_t>(integrand.multiplier_space.local_dofs()) *
                         integrand.multiplier_space.components() * 3) {}

double PointIntegrator::integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) {
  const MappedTriangle& mt = image.triangle;
  Point xi_corner[Piece::kMaxVertices];
  for (int v = 0; v < piece.n; ++v) xi_corner[v] = image.pull_back(piece.v[v]);
  const auto& rule = triangle_rule(image.degree);
  for (int t = 1; t + 1 < piece.n; ++t) {
    const Point tri[3] = {piece.v[0], piece.v[t], piece.v[t + 1]};
    const Point guess[3] = {xi_corner[0], xi_corner[t], xi_corner[t + 1]};
    const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
    for (const RulePoint& q : rule) {
      const Point y = from_reference(tri, q.xi);
      // y relative to image.origin (0 where the map is not affine)
      MapValue mv;
      const Point xi = mt.affine ? image.pull_back(y) : mt.pull_back(y, from_reference(guess, q.xi), mv);
      const double det = mt.affine ? mt.affine_det : det2(mv.jac);
      if (!(det > 0)) throw Error("the map folds solid triangle " + std::to_string(mt.k));
      add_reference_point(kf, integrand_.fluid.to_reference(kf, y, image.origin), mt.k, xi, area * q.weight / det,
                          mt.affine ? mt.affine_value.jac : mv.jac, block);
    }
  }
  return piece.area();
}

void PointIntegrator::add_reference_point(int kf, Point eta, int ks, Point xi, double ds, const double jac[2][2],
                                          LocalBlock& block) {
  integrand_.fluid.evaluate(kf, eta, fluid_values_.data());
  integrand_.multiplier.evaluate(ks, xi, multiplier_values_.data());
  ++counts_.points;
  const int fluid_components = integrand_.fluid_space.components();
  const int multiplier_components = integrand_.multiplier_space.components();
  auto phi_at = [&](int j, int c) { return &fluid_values_[(static_cast<size_t>(j) * fluid_components + c) * 3]; };
  auto psi_at = [&](int i, int c) { return &multiplier_values_[(static_cast<size_t>(i) * multiplier_components + c) * 3]; };
  const double c1 = integrand_.c1 * ds, c2 = integrand_.c2 * ds;
  const bool chain = integrand_.chain;
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    for (int j = pair.fluid_first; j < pair.fluid_last; ++j) {
      const double* phi = phi_at(j, pair.fluid_component);
      // grad_s (phi o X)_b = sum_a d_a phi * dX_a/ds_b
      const double g0 = phi[1] * jac[0][0] + phi[2] * jac[1][0];
      const double g1 = phi[1] * jac[0][1] + phi[2] * jac[1][1];
      double* column = block.column(j);
      for (int i = pair.solid_first; i < pair.solid_last; ++i) {
        const double* psi = psi_at(i, pair.solid_component);
        double v = c2 * psi[0] * phi[0];
        if (chain) v += c1 * (psi[1] * g0 + psi[2] * g1);
        column[i] += v;
      }
    }
  }
  if (chain || integrand_.c1 == 0) return;
  // The listings' product: the pair index is the vector component.
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) {
      const double w = c1 * jac[a][c];
      const ComponentPair &row_pair = pairs[a], &column_pair = pairs[c];
      for (int j = column_pair.fluid_first; j < column_pair.fluid_last; ++j) {
        const double* phi = phi_at(j, column_pair.fluid_component);
        double* column = block.column(j);
        for (int i = row_pair.solid_first; i < row_pair.solid_last; ++i) {
          const double* psi = psi_at(i, row_pair.solid_component);
          column[i] += w * (psi[1] * phi[1] + psi[2] * phi[2]);
        }
      }
    }
}

}  // namespace dlmfsi
