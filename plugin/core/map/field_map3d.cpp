#include "map/field_map3d.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "buffer_room.hpp"
#include "errors.hpp"
#include "fe/lattice3d.hpp"
#include "parallel/on_threads.hpp"
#include "fe/polynomial_fit.hpp"

namespace dlmfsi {

namespace {

const Point3 kCorners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

}  // namespace

int FieldMap3::fit_degree(const Basis3* const space[3], const int comp[3]) {
  int degree = 0;
  for (int a = 0; a < 3; ++a) {
    if (comp[a] < 0 || comp[a] >= space[a]->components()) throw Error("map component out of range");
    const int d = polynomial_degree(*space[a], {comp[a]});
    if (d < 0) return -1;
    degree = std::max(degree, d);
  }
  return degree < 1 || degree > kMaxMapDegree3 ? -1 : degree;
}

FieldMap3::FieldMap3(const Mesh3& solid, const Basis3* const space[3], const double* const coef[3], const int comp[3],
                     const PolynomialBasis3* const fit[3], int threads, RawRoom<double>* room) {
  for (int a = 0; a < 3; ++a) {
    part_[a] = {space[a], coef[a], comp[a], 0, 0};
    space[a]->component_dofs(comp[a], part_[a].first, part_[a].last);
    for (int i = 0; i < 4; ++i) corner_dof_[a][i] = -1;
  }
  degree_ = fit_degree(space, comp);
  if (degree_ < 0) return;  // not polynomial (or constant): evaluate the map itself
  const int nm = monomial_count3(degree_), size = solid.size();
  corner_exact_.assign(size, 1);
  std::unique_ptr<PolynomialBasis3> own[3];
  const PolynomialBasis3* used[3] = {nullptr, nullptr, nullptr};
  for (int a = 0; a < 3; ++a) {
    const Part& p = part_[a];
    if (fit && fit[a] && fit[a]->degree() == degree_) {
      used[a] = fit[a];
    } else {
      // X, Y and Z are often the same space and component (functions of one scalar space): one fit.
      for (int b = 0; b < a && !used[a]; ++b)
        if (part_[b].space == p.space && part_[b].comp == p.comp) used[a] = used[b];
      if (!used[a]) {
        own[a] = std::make_unique<PolynomialBasis3>(*p.space, solid, degree_, std::vector<int>{p.comp});
        used[a] = own[a].get();
      }
    }
    const PolynomialBasis3& poly = *used[a];
    if (!poly.fitted()) {
      degree_ = -1;
      corner_exact_.clear();
      return;
    }
    const int nc = p.space->components();
    // The Lagrange dof at each corner, from the shared fit's values there (1 for it, 0 for the others).
    if (solid.size() > 0) {
      double v[monomial_count3(kMaxLatticeDegree)];
      for (int i = 0; i < 4; ++i) {
        monomial_values3(degree_, kCorners[i], v);
        int one = -1, count = 0;
        bool others_zero = true;
        const double* c = poly.coefficients(0);
        for (size_t f = 0; f < poly.functions().size(); ++f, c += nm) {
          double s = 0;
          for (int m = 0; m < nm; ++m) s += c[m] * v[m];
          if (std::fabs(s - 1) < 1e-9) {
            one = poly.functions()[f] / nc;
            ++count;
          } else if (std::fabs(s) > 1e-9) {
            others_zero = false;
          }
        }
        corner_dof_[a][i] = count == 1 && others_zero ? one : -1;
      }
    }
    for (int k = 0; k < size; ++k)
      if (!poly.shared(k)) corner_exact_[k] = 0;
  }
  monomial_coef_ = (room ? *room : own_room_).room(static_cast<size_t>(size) * 3 * nm);
  on_shares(threads_for(threads, size, 8192), size, [&](int first, int last) {
    for (int a = 0; a < 3; ++a)
      field_monomials(*part_[a].space, part_[a].coef, *used[a], nm, first, last, monomial_coef_,
                      static_cast<size_t>(a) * nm, 3 * static_cast<size_t>(nm));
  });
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 4; ++i)
      if (corner_dof_[a][i] < 0) corner_exact_.assign(solid.size(), 0);
}

bool FieldMap3::coefficients(int k, double* cx, double* cy, double* cz) const {
  if (!monomial_coef_) return false;
  const int nm = monomial_count3(degree_);
  const double* c = &monomial_coef_[static_cast<size_t>(k) * 3 * nm];
  std::copy(c, c + nm, cx);
  std::copy(c + nm, c + 2 * nm, cy);
  std::copy(c + 2 * nm, c + 3 * nm, cz);
  return true;
}

bool FieldMap3::corners(int k, Point3* out) const {
  if (corner_exact_.empty() || !corner_exact_[k]) return false;
  thread_local std::vector<int> dofs;
  double x[3][4];
  for (int a = 0; a < 3; ++a) {
    const Part& p = part_[a];
    dofs.resize(p.space->local_dofs());
    p.space->dofs(k, dofs.data());
    for (int i = 0; i < 4; ++i) x[a][i] = p.coef[dofs[corner_dof_[a][i]]];
  }
  for (int i = 0; i < 4; ++i) out[i] = {x[0][i], x[1][i], x[2][i]};
  return true;
}

MapValue3 FieldMap3::evaluate(int k, Point3 xi) const {
  MapValue3 v{};
  thread_local std::vector<double> out;
  thread_local std::vector<int> dofs;
  double* x[3] = {&v.x.x, &v.x.y, &v.x.z};
  for (int a = 0; a < 3; ++a) {
    const Part& p = part_[a];
    const int nc = p.space->components();
    out.resize(static_cast<size_t>(p.space->local_dofs()) * nc * 4);
    dofs.resize(p.space->local_dofs());
    p.space->evaluate(k, xi, out.data());
    p.space->dofs(k, dofs.data());
    double val = 0, g[3] = {0, 0, 0};
    for (int df = p.first; df < p.last; ++df) {
      const double c = p.coef[dofs[df]];
      const double* f = &out[(df * nc + p.comp) * 4];
      val += c * f[0];
      for (int i = 0; i < 3; ++i) g[i] += c * f[1 + i];
    }
    *x[a] = val;
    for (int i = 0; i < 3; ++i) v.jac[a][i] = g[i];
  }
  return v;
}

}  // namespace dlmfsi
