#include "integration/quadrature_method.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sides/report.hpp"
#include "sides/sides.hpp"
#include "geometry/predicates.hpp"
#include "fe/rules.hpp"

namespace dlmfsi {

QuadratureMethod::QuadratureMethod(const FluidSide& fluid, FluidSearch& search, const Integrand& integrand,
                                   int map_degree, int qforder, double tol, CouplingReport& counts)
    : fluid_(fluid), search_(search), points_(integrand, counts), product_degree_(integrand.product_degree),
      fluid_degree_(integrand.fluid_degree), multiplier_degree_(integrand.multiplier_degree), map_degree_(map_degree),
      qforder_(qforder),
      max_depth_(std::min(12, std::max(0, static_cast<int>(std::ceil(std::log(1 / std::max(tol, 1e-300)) / std::log(4.0)))))),
      counts_(counts) {}

double QuadratureMethod::integrate(const MappedTriangle& mt, LocalBlock& block) {
  const double solid_jacobian = area2(mt.solid[0], mt.solid[1], mt.solid[2]);  // ds = this * dxi
  const auto& rule = triangle_rule(rule_degree(mt));
  double outside = 0;
  std::vector<Leaf>& stack = stack_;
  stack.assign(1, {{{0, 0}, {1, 0}, {0, 1}}, {mt.image[0], mt.image[1], mt.image[2]}, 0});
  auto image_of = [&](Point xi) { return mt.affine ? from_reference(mt.image, xi) : mt.at(xi).x; };
  while (!stack.empty()) {
    const Leaf s = stack.back();
    stack.pop_back();
    if (s.depth < max_depth_ && !one_fluid_triangle(s.img)) {
      const Point m[3] = {0.5 * (s.ref[0] + s.ref[1]), 0.5 * (s.ref[1] + s.ref[2]), 0.5 * (s.ref[2] + s.ref[0])};
      const Point mi[3] = {image_of(m[0]), image_of(m[1]), image_of(m[2])};
      stack.push_back({{s.ref[0], m[0], m[2]}, {s.img[0], mi[0], mi[2]}, s.depth + 1});
      stack.push_back({{m[0], s.ref[1], m[1]}, {mi[0], s.img[1], mi[1]}, s.depth + 1});
      stack.push_back({{m[2], m[1], s.ref[2]}, {mi[2], mi[1], s.img[2]}, s.depth + 1});
      stack.push_back({{m[1], m[2], m[0]}, {mi[1], mi[2], mi[0]}, s.depth + 1});
      continue;
    }
    ++counts_.pieces;
    const double ref_area = 0.5 * area2(s.ref[0], s.ref[1], s.ref[2]);
    for (const RulePoint& q : rule) {
      const Point xi = from_reference(s.ref, q.xi);
      MapValue mv = mt.affine ? mt.affine_value : mt.at(xi);
      if (mt.affine) mv.x = from_reference(mt.image, xi);
      const double ds = q.weight * ref_area * solid_jacobian;
      const int kf = search_.locate(mv.x, hint_);
      if (kf < 0) {
        outside += ds * std::fabs(det2(mv.jac));
        continue;
      }
      hint_ = kf;
      block.enter_fluid_element(fluid_.dofs(kf));
      points_.add_point(kf, mv.x, mt.k, xi, ds, mv.jac, block);
    }
  }
  return outside;
}

int QuadratureMethod::rule_degree(const MappedTriangle& mt) {
  if (qforder_ >= 0) return qforder_;
  if (mt.affine) return product_degree_;
  int degree;
  if (map_degree_ >= 1 && fluid_degree_ >= 0 && multiplier_degree_ >= 0)
    degree = std::min(kMaxQforder, multiplier_degree_ + fluid_degree_ * map_degree_);
  else
    degree = nonlinear_rule_degree(product_degree_, mt.nonlinearity);
  counts_.curved_rule_degree = std::max(counts_.curved_rule_degree, degree);
  return degree;
}

bool QuadratureMethod::one_fluid_triangle(const Point img[3]) {
  const int k = search_.locate(img[0], hint_);
  if (k < 0) return false;
  hint_ = k;
  const Mesh& mesh = fluid_.mesh();
  for (int i = 1; i < 3; ++i)
    for (int e = 0; e < 3; ++e)
      if (orient2d(mesh.vertex(k, e), mesh.vertex(k, (e + 1) % 3), img[i]) < 0) return false;
  return true;
}

}  // namespace dlmfsi
