#include "map/field_map.hpp"

#include <algorithm>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

#include "buffer_room.hpp"
#include "errors.hpp"
#include "fe/lattice.hpp"
#include "parallel/on_threads.hpp"
#include "fe/polynomial_fit.hpp"
#include "map/element_map.hpp"

namespace dlmfsi {

int FieldMap::fit_degree(const Basis& space_x, int comp_x, const Basis& space_y, int comp_y) {
  int degree = 0;
  for (const auto& [space, comp] : {std::pair<const Basis*, int>{&space_x, comp_x}, {&space_y, comp_y}}) {
    if (comp < 0 || comp >= space->components()) throw Error("map component out of range");
    const int d = polynomial_degree(*space, {comp});
    if (d < 0) return -1;
    degree = std::max(degree, d);
  }
  return degree < 1 || degree > TriangleMap::kMaxDegree ? -1 : degree;
}

FieldMap::FieldMap(const Mesh& solid, const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y,
                   const double* coef_y, int comp_y, const PolynomialBasis* fit_x, const PolynomialBasis* fit_y,
                   int threads, RawRoom<double>* room) {
  part_[0] = {&space_x, coef_x, comp_x, 0, 0};
  part_[1] = {&space_y, coef_y, comp_y, 0, 0};
  degree_ = fit_degree(space_x, comp_x, space_y, comp_y);
  for (auto& p : part_) p.space->component_dofs(p.comp, p.first, p.last);
  if (degree_ < 0) return;  // not polynomial (or constant): evaluate the map itself
  // X on triangle k = sum over the component's dofs of (dof value) * (basis polynomial).
  const PolynomialBasis* fit[2] = {nullptr, nullptr};
  std::unique_ptr<PolynomialBasis> own[2];
  for (int a = 0; a < 2; ++a) {
    const Part& p = part_[a];
    const PolynomialBasis* given = a == 0 ? fit_x : fit_y;
    if (given && given->degree() == degree_) {
      fit[a] = given;
    } else if (a == 1 && p.space == part_[0].space && p.comp == part_[0].comp) {
      fit[a] = fit[0];  // X and Y are often the same space and component (two functions of one scalar space)
    } else {
      own[a] = std::make_unique<PolynomialBasis>(*p.space, solid, degree_, std::vector<int>{p.comp});
      fit[a] = own[a].get();
    }
    if (!fit[a]->fitted()) {
      degree_ = -1;
      return;
    }
  }
  const int nm = monomial_count(degree_), size = solid.size();
  monomial_coef_ = (room ? *room : own_room_).room(static_cast<size_t>(size) * 2 * nm);
  // X and Y on one space, component and fit (two functions of one scalar space): both in one pass.
  const bool together = fit[0] == fit[1] && part_[0].space == part_[1].space && part_[0].comp == part_[1].comp;
  const double* values[2] = {part_[0].coef, part_[1].coef};
  on_shares(threads_for(threads, size, 8192), size, [&](int first, int last) {
    if (together) {
      field_monomials(*part_[0].space, values, 2, *fit[0], nm, first, last, monomial_coef_, 0,
                      2 * static_cast<size_t>(nm));
      return;
    }
    for (int a = 0; a < 2; ++a)
      field_monomials(*part_[a].space, part_[a].coef, *fit[a], nm, first, last, monomial_coef_,
                      static_cast<size_t>(a) * nm, 2 * static_cast<size_t>(nm));
  });
}

bool FieldMap::coefficients(int k, double* cx, double* cy) const {
  if (!monomial_coef_) return false;
  const int nm = monomial_count(degree_);
  const double* c = &monomial_coef_[static_cast<size_t>(k) * 2 * nm];
  if (nm == 3) {  // degree 1: six copies, not two calls to copy a variable length
    cx[0] = c[0], cx[1] = c[1], cx[2] = c[2];
    cy[0] = c[3], cy[1] = c[4], cy[2] = c[5];
    return true;
  }
  std::copy(c, c + nm, cx);
  std::copy(c + nm, c + 2 * nm, cy);
  return true;
}

MapValue FieldMap::evaluate(int k, Point xi) const {
  MapValue v{};
  // X and Y are often two components of one vector function: evaluate that space once.
  const bool shared = part_[0].space == part_[1].space && part_[0].coef == part_[1].coef;
  thread_local std::vector<double> out;
  thread_local std::vector<int> dofs;
  for (int a = 0; a < 2; ++a) {
    const Part& p = part_[a];
    const int nc = p.space->components();
    if (a == 0 || !shared) {
      out.resize(static_cast<size_t>(p.space->local_dofs()) * nc * 3);
      dofs.resize(p.space->local_dofs());
      p.space->evaluate(k, xi, out.data());
      p.space->dofs(k, dofs.data());
    }
    double val = 0, dx = 0, dy = 0;
    for (int df = p.first; df < p.last; ++df) {
      const double c = p.coef[dofs[df]];
      const double* f = &out[(df * nc + p.comp) * 3];
      val += c * f[0];
      dx += c * f[1];
      dy += c * f[2];
    }
    (a == 0 ? v.x.x : v.x.y) = val;
    v.jac[a][0] = dx;
    v.jac[a][1] = dy;
  }
  return v;
}

}  // namespace dlmfsi
