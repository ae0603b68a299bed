// Fast evaluation of a Basis: on each element the basis functions are polynomials in the reference
// coordinates (BasisFit), evaluated by monomials, with physical derivatives through the element's affine
// map (AffineElementMaps). All elements are checked at construction.
#pragma once
#include <cstddef>
#include <vector>

#include "fe/affine_element_maps.hpp"
#include "fe/basis.hpp"
#include "fe/basis_fit.hpp"
#include "fe/lattice.hpp"
#include "mesh/mesh.hpp"
#include "fe/points_evaluation.hpp"

namespace dlmfsi {

class PolynomialBasis {
 public:
  // degree: the basis degree on the listed components (polynomial_degree), or -1 to evaluate the basis
  // itself at every point. Only the listed components, on the local dofs that carry them, are computed.
  // The fit of the first element is checked at two points off the lattice; if it misses the basis (an
  // element that is not polynomial of that degree), every evaluation goes to the basis itself.
  PolynomialBasis(const Basis& basis, const Mesh& mesh, int degree, const std::vector<int>& components);

  // Same layout as Basis::evaluate; only the listed components, on their dofs, are written.
  // Safe to call from several threads when fitted() (no call into the basis then).
  void evaluate(int k, Point xi, double* out) const;

  // The fitted functions at n points of element k at once (fitted() only): evaluate_at_points.
  void evaluate_points(int k, const Point* xi, int n, double* value, double* dx, double* dy) const {
    evaluate_at_points(fit_, k, maps_.inverse_jacobian(k), xi, n, value, dx, dy);
  }

  // Degree 0 or 1 only: the fitted functions' values at xi and their (constant) physical gradients, one
  // entry per function.
  void evaluate_affine(int k, Point xi, double* value, double* dx, double* dy) const {
    const double* c = fit_.coefficients(k);
    const double* j = maps_.inverse_jacobian(k);
    const int nm = fit_.terms();
    const size_t width = fit_.functions().size();
    for (size_t f = 0; f < width; ++f, c += nm) {
      if (nm == 1) {
        value[f] = c[0];
        dx[f] = dy[f] = 0;
        continue;
      }
      // monomials 1, xi1, xi2
      value[f] = c[0] + c[1] * xi.x + c[2] * xi.y;
      dx[f] = c[1] * j[0] + c[2] * j[2];
      dy[f] = c[1] * j[1] + c[2] * j[3];
    }
  }

  // A hint that element k comes soon: its fit and map brought towards the cache.
  void prefetch(int k) const {
    fit_.prefetch(k);
    maps_.prefetch(k);
  }

  // The reference coordinates of point x in element k (the inverse of the element's affine map).
  Point to_reference(int k, Point x) const { return maps_.to_reference(k, x); }
  // The same for x given relative to origin (AffineElementMaps::to_reference).
  Point to_reference(int k, Point x_local, Point origin) const { return maps_.to_reference(k, x_local, origin); }
  // d xi / d x on element k (AffineElementMaps::inverse_jacobian).
  const double* inverse_jacobian(int k) const { return maps_.inverse_jacobian(k); }

  // The fit (BasisFit's accessors).
  bool fitted() const { return fit_.fitted(); }
  int degree() const { return fit_.degree(); }
  int terms() const { return fit_.terms(); }
  const std::vector<int>& functions() const { return fit_.functions(); }
  bool shared(int k) const { return fit_.shared(k); }
  int twin(int f) const { return fit_.twin(f); }
  const double* coefficients(int k) const { return fit_.coefficients(k); }
  const double* derivative_coefficients(int k) const { return fit_.derivative_coefficients(k); }

 private:
  template <int NM>
  void evaluate_fitted(const double* coef, const double* jac, const double* v, const double* d1, const double* d2,
                       double* out) const;
  const Basis& basis_;
  AffineElementMaps maps_;
  BasisFit fit_;
};

}  // namespace dlmfsi
