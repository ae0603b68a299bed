// X given by finite element functions on the solid mesh.
#pragma once
#include <memory>

#include "buffer_room.hpp"
#include "fe/basis.hpp"
#include "map/solid_map.hpp"
#include "mesh/mesh.hpp"
#include "fe/polynomial_basis.hpp"

namespace dlmfsi {

// X = (sum_i x_i phi_i^cx, sum_i y_i phi_i^cy): components of finite element functions on the solid mesh
// (two scalar functions, or two components of one vector function). For polynomial spaces the monomial
// coefficients of X on every solid triangle are computed once, here, from the spaces' fits on the map's
// components: fit_x and fit_y when the caller keeps them across calls (PolynomialBasis(space, solid,
// fit_degree(...), {comp})), otherwise fitted here. With threads > 1 they are computed on that many threads:
// the spaces' dofs() must then be safe to call from several threads at once. They are kept in room when the
// caller gives one (and keeps it, for one map at a time, past this map's life: a time loop's maps then reuse
// its memory).
class FieldMap : public SolidMap {
 public:
  FieldMap(const Mesh& solid, const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y,
           const double* coef_y, int comp_y, const PolynomialBasis* fit_x = nullptr,
           const PolynomialBasis* fit_y = nullptr, int threads = 1, RawRoom<double>* room = nullptr);
  // The degree the map is fitted to: the higher polynomial degree of the two components, or -1 when one is
  // not polynomial or the degree lies outside 1..6 (the map is then evaluated through the spaces). Throws
  // Error for a component out of range.
  static int fit_degree(const Basis& space_x, int comp_x, const Basis& space_y, int comp_y);
  MapValue evaluate(int k, Point xi) const override;
  int degree() const override { return degree_; }
  bool coefficients(int k, double* cx, double* cy) const override;
  void prefetch(int k) const override {
    if (monomial_coef_) __builtin_prefetch(&monomial_coef_[static_cast<size_t>(k) * 2 * monomial_count(degree_)]);
  }

 private:
  struct Part {
    const Basis* space;
    const double* coef;
    int comp, first, last;
  };
  Part part_[2];
  int degree_ = -1;
  RawRoom<double> own_room_;         // when the caller gives no room
  double* monomial_coef_ = nullptr;  // per triangle: x then y coefficients
};

}  // namespace dlmfsi
