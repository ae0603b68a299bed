// A map given by finite element functions on the solid mesh (the FreeFEM functions [X, Y, Z]).
#pragma once
#include <memory>
#include <vector>

#include "buffer_room.hpp"
#include "fe/basis.hpp"
#include "mesh/mesh3d.hpp"
#include "fe/polynomial_basis3d.hpp"
#include "map/solid_map3d.hpp"

namespace dlmfsi {

// X = (sum_i x_i phi_i^cx, sum_i y_i phi_i^cy, sum_i z_i phi_i^cz): components of finite element functions
// on the solid mesh (three scalar functions, or components of one vector function). For polynomial
// spaces the monomial coefficients of X on every tetrahedron are computed once, here, from the spaces' fits
// (given in fit[] when the caller keeps them across calls, otherwise fitted here). With threads > 1 they are
// computed on that many threads: the spaces' dofs() must then be safe to call from several threads at once.
// They are kept in room when the caller gives one (and keeps it, for one map at a time, past this map's
// life: a time loop's maps then reuse its memory).
class FieldMap3 : public SolidMap3 {
 public:
  FieldMap3(const Mesh3& solid, const Basis3* const space[3], const double* const coef[3], const int comp[3],
            const PolynomialBasis3* const fit[3] = nullptr, int threads = 1, RawRoom<double>* room = nullptr);
  // The degree the map is fitted to: the highest polynomial degree of the three components, or -1 when one
  // is not polynomial or the degree lies outside 1..6. Throws Error for a component out of range.
  static int fit_degree(const Basis3* const space[3], const int comp[3]);
  MapValue3 evaluate(int k, Point3 xi) const override;
  int degree() const override { return degree_; }
  bool coefficients(int k, double* cx, double* cy, double* cz) const override;
  bool corners(int k, Point3* out) const override;

 private:
  struct Part {
    const Basis3* space;
    const double* coef;
    int comp, first, last;
  };
  Part part_[3];
  int degree_ = -1;
  RawRoom<double> own_room_;         // when the caller gives no room
  double* monomial_coef_ = nullptr;  // per tetrahedron: x, y then z coefficients
  // Per part and corner of the reference tetrahedron: the local dof whose basis function is 1 there while
  // the part's others are 0 (a Lagrange dof at the vertex), or -1; valid on tetrahedra of the shared fit.
  int corner_dof_[3][4];
  std::vector<char> corner_exact_;  // per tetrahedron: every part uses the shared fit and has corner dofs
};

}  // namespace dlmfsi
