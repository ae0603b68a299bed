#include "integration/quadrature_method3d.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sides/report.hpp"
#include "sides/sides3d.hpp"
#include "errors.hpp"
#include "geometry/predicates3d.hpp"
#include "geometry/red_refinement3d.hpp"
#include "fe/rules.hpp"

namespace dlmfsi {

QuadratureMethod3::QuadratureMethod3(const FluidSide3& fluid, FluidSearch3& search, const Integrand3& integrand,
                                     int qforder, int subdivide, CouplingReport& counts)
    : fluid_(fluid), search_(search), integrand_(integrand), qforder_(qforder), subdivide_(std::max(0, subdivide)),
      points_(integrand, counts), counts_(counts) {}

double QuadratureMethod3::integrate(const MappedTet& mt, LocalBlock& block) {
  const double solid_volume = std::fabs(volume6(mt.solid[0], mt.solid[1], mt.solid[2], mt.solid[3])) / 6;
  const auto& rule = tetrahedron_rule(rule_degree(mt));
  double outside = 0;
  located_.clear();
  for (const auto& sub : reference_subdivision(subdivide_)) {
    const double fraction = volume6(sub[0], sub[1], sub[2], sub[3]);  // of the reference tetrahedron's volume
    for (const RulePoint3& q : rule) {
      Located p{};
      p.point.xi = from_reference(sub.data(), q.xi);
      p.point.weight = q.weight * fraction * solid_volume;  // ds
      Point3 y;
      double det = mt.affine_det;
      if (mt.affine) {
        y = from_reference(mt.image, p.point.xi);
      } else {
        const MapValue3 mv = mt.at(p.point.xi);
        y = mv.x;
        det = det3(mv.jac);
        if (!(det > 0)) throw Error("the map folds solid tetrahedron " + std::to_string(mt.k));
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) p.point.jac[3 * a + b] = mv.jac[a][b];
      }
      p.kf = find(y, p.point.eta);
      if (p.kf < 0) {
        outside += p.point.weight * det;  // image volume
        continue;
      }
      located_.push_back(p);
    }
  }
  // One evaluation of the bases per fluid tetrahedron met (points in rule order within it).
  std::stable_sort(located_.begin(), located_.end(), [](const Located& a, const Located& b) { return a.kf < b.kf; });
  for (size_t i = 0; i < located_.size();) {
    size_t j = i;
    group_.clear();
    for (; j < located_.size() && located_[j].kf == located_[i].kf; ++j) group_.push_back(located_[j].point);
    ++counts_.pieces;
    block.enter_fluid_element(fluid_.dofs(located_[i].kf));
    points_.add_points(mt, located_[i].kf, group_.data(), static_cast<int>(group_.size()), block);
    i = j;
  }
  return outside;
}

int QuadratureMethod3::find(Point3 y, Point3& eta) {
  // A walk on the fluid's affine frames from the last point's tetrahedron: where all barycentric coordinates
  // (1 - sum eta, eta) exceed kMargin, y lies strictly inside (the frames' round-off, about
  // eps * cond(E) * |x| / diam, stays far below kMargin for any usable mesh), and no other tetrahedron holds
  // it; where the most negative one is below -kMargin, step across that face. Near a face (or a boundary, or
  // after many steps) the exact walk decides (FluidSearch3::locate: exact orient3d signs).
  constexpr double kMargin = 1e-6;
  const Mesh3& mesh = fluid_.mesh();
  int k = hint_;
  for (int step = 0; step < 64; ++step) {
    eta = integrand_.fluid.to_reference(k, y);
    const double lambda[4] = {1 - eta.x - eta.y - eta.z, eta.x, eta.y, eta.z};
    int low = 0;
    for (int i = 1; i < 4; ++i)
      if (lambda[i] < lambda[low]) low = i;
    if (lambda[low] > kMargin) return hint_ = k;
    if (lambda[low] > -kMargin || mesh.neighbours[k][low] < 0) break;
    k = mesh.neighbours[k][low];
  }
  const int kf = search_.locate(y, k);
  if (kf < 0) return -1;
  eta = integrand_.fluid.to_reference(kf, y);
  return hint_ = kf;
}

int QuadratureMethod3::rule_degree(const MappedTet& mt) {
  if (qforder_ >= 0) return qforder_;
  if (mt.affine) return integrand_.product_degree;
  const int m = mt.fitted_degree();
  int degree;
  if (m >= 1 && integrand_.fluid_degree >= 0 && integrand_.multiplier_degree >= 0)
    degree = std::min(40, integrand_.multiplier_degree + integrand_.fluid_degree * m);
  else
    degree = std::min(40, integrand_.product_degree + 8);  // a map of unknown degree: smooth, not polynomial
  counts_.curved_rule_degree = std::max(counts_.curved_rule_degree, degree);
  return degree;
}

}  // namespace dlmfsi
