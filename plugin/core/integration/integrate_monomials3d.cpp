#include "integration/integrate_monomials3d.hpp"

#include <cmath>

#include "sides/report.hpp"
#include "sides/sides3d.hpp"
#include "fe/rules.hpp"

namespace dlmfsi {

bool MonomialIntegrator3::applies(const Integrand3& integrand) {
  const PolynomialBasis3 &fluid = integrand.fluid, &multiplier = integrand.multiplier;
  return fluid.fitted() && multiplier.fitted() && fluid.degree() >= 2 && fluid.degree() < kMaxLatticeDegree &&
         multiplier.degree() <= 1 && (integrand.chain || integrand.c1 == 0);
}

MonomialIntegrator3::MonomialIntegrator3(const Integrand3& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), points_(integrand, counts),
      fluid_functions_(static_cast<int>(integrand.fluid.functions().size())),
      multiplier_functions_(static_cast<int>(integrand.multiplier.functions().size())),
      moment_(monomial_count3(integrand.fluid.degree() + 1)), first_(4 * static_cast<size_t>(fluid_functions_)),
      gradient_sum_(3 * static_cast<size_t>(fluid_functions_)), value_(multiplier_functions_),
      gradient_(3 * static_cast<size_t>(multiplier_functions_)), q_(3 * static_cast<size_t>(multiplier_functions_)) {}

double MonomialIntegrator3::integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) {
  const PolynomialBasis3 &fluid = integrand_.fluid, &multiplier = integrand_.multiplier;
  if (!fluid.integrates_moments(kf)) return points_.integrate(image, kf, piece, block);
  const MappedTet& mt = image.tetrahedron;
  // The rule of degree d + 1 on the piece's tetrahedra, in the fluid element's reference coordinates.
  const auto& rule = tetrahedron_rule_for_polynomials(fluid.moment_degree());
  Point3 eta_corner[Piece3::kMaxVertices];
  for (int v = 0; v < piece.n; ++v) eta_corner[v] = fluid.to_reference(kf, piece.v[v], image.origin);
  int n = 0;
  double volume = 0;
  piece.for_each_tetrahedron_index([&](int i0, int i1, int i2, int i3) {
    const double vol = std::fabs(volume6(piece.v[i0], piece.v[i1], piece.v[i2], piece.v[i3])) / 6;
    volume += vol;
    const Point3 tet[4] = {eta_corner[i0], eta_corner[i1], eta_corner[i2], eta_corner[i3]};
    if (eta_.size() < static_cast<size_t>(n) + rule.size()) {
      eta_.resize(n + rule.size());
      weight_.resize(n + rule.size());
    }
    for (const RulePoint3& rp : rule) {
      eta_[n] = from_reference(tet, rp.xi);
      weight_[n++] = vol * rp.weight;
    }
  });
  counts_.points += n;
  if (!(volume > 0)) return volume;
  fluid.moments(eta_.data(), weight_.data(), n, moment_.data());
  fluid.integrate_moments(kf, moment_.data(), first_.data(), gradient_sum_.data());
  // The multiplier at the centroid, and q_i = (grad_y psi_i . e_k)_k with grad_y psi = (dX/ds)^-T grad_s psi.
  const Point3 eta_c{moment_[1] / moment_[0], moment_[2] / moment_[0], moment_[3] / moment_[0]};
  const Point3 centroid = fluid.from_reference(kf, eta_c, image.origin);  // relative to image.origin
  multiplier.evaluate_affine(mt.k, mt.affine_reference(centroid, image.origin), value_.data(), gradient_.data());
  const double(&j)[3][3] = mt.affine_value.jac;
  const double det = mt.affine_det, mass = integrand_.c2 / det, stiff = integrand_.c1 / det;
  const Point3 e[3] = {fluid.edge(kf, 0), fluid.edge(kf, 1), fluid.edge(kf, 2)};
  // q_i = (grad_s psi_i . J^-1 e_k)_k, J^-1 e_k by Cramer's rule with J's columns
  const Point3 c0{j[0][0], j[1][0], j[2][0]}, c1{j[0][1], j[1][1], j[2][1]}, c2{j[0][2], j[1][2], j[2][2]};
  Point3 ds[3];
  for (int k = 0; k < 3; ++k)
    ds[k] = (1 / det) * Point3{dot(e[k], cross(c1, c2)), dot(c0, cross(e[k], c2)), dot(c0, cross(c1, e[k]))};
  for (int s = 0; s < multiplier_functions_; ++s) {
    const Point3 gs{gradient_[3 * s], gradient_[3 * s + 1], gradient_[3 * s + 2]};
    for (int k = 0; k < 3; ++k) q_[3 * s + k] = dot(gs, ds[k]);
  }
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      const int f = pair.fluid_functions[a];
      const double* o = &first_[4 * static_cast<size_t>(f)];
      // the sums scaled by c2 / det and c1 / det once for all the multiplier functions
      const double A = mass * o[0];
      const double B[3] = {mass * o[1] - eta_c.x * A, mass * o[2] - eta_c.y * A, mass * o[3] - eta_c.z * A};
      // c1 / det J^T int grad_y phi: the gradient term's fluid side
      const double* g = &gradient_sum_[3 * static_cast<size_t>(f)];
      double jg[3];
      for (int b = 0; b < 3; ++b) jg[b] = stiff * (g[0] * j[0][b] + g[1] * j[1][b] + g[2] * j[2][b]);
      double* col = block.column(pair.fluid_first + static_cast<int>(a)) + pair.solid_first;
      for (size_t b = 0; b < pair.solid_functions.size(); ++b) {
        const int s = pair.solid_functions[b];
        const double* gs = &gradient_[3 * static_cast<size_t>(s)];
        const double* q = &q_[3 * static_cast<size_t>(s)];
        col[b] += value_[s] * A + q[0] * B[0] + q[1] * B[1] + q[2] * B[2] + gs[0] * jg[0] + gs[1] * jg[1] + gs[2] * jg[2];
      }
    }
  }
  return volume;
}

}  // namespace dlmfsi
