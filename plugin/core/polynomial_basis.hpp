// Fast evaluation of a Basis. On each element the basis functions are polynomials in the reference
// coordinates (polynomial elements on straight triangles): they are fitted on the degree-d lattice, then
// evaluated by monomials, with physical derivatives through the element's affine map. Elements that are
// affine-equivalent (P0, P1, P1b, P2, P1nc, ...) share one fit: each element is checked against it with a
// single basis evaluation at a generic point, and fitted on its own only where it differs (e.g. where dof
// orientation or sign depends on the element). All elements are checked at construction.
#pragma once
#include <cstddef>
#include <vector>

#include "basis.hpp"
#include "lattice.hpp"
#include "mesh.hpp"

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

  // The fitted functions at n points of element k at once (fitted() only), monomials formed once per point:
  // value[f * n + p] for the f-th of functions() at point p, and when dx and dy are not null the physical
  // first derivatives in the same layout.
  void evaluate_points(int k, const Point* xi, int n, double* value, double* dx, double* dy) const;

  // Degree 0 or 1 only: the fitted functions' values at xi and their (constant) physical gradients, one
  // entry per function.
  void evaluate_affine(int k, Point xi, double* value, double* dx, double* dy) const {
    const double* c = coefficients(k);
    const double* j = &inverse_jacobian_[4 * static_cast<size_t>(k)];
    const size_t width = functions_.size();
    for (size_t f = 0; f < width; ++f, c += nm_) {
      if (nm_ == 1) {
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

  // The reference coordinates of point x in element k (the inverse of the element's affine map).
  Point to_reference(int k, Point x) const {
    const double* j = &inverse_jacobian_[4 * static_cast<size_t>(k)];
    const Point d = x - mesh_.vertex(k, 0);
    return {j[0] * d.x + j[1] * d.y, j[2] * d.x + j[3] * d.y};
  }

  bool fitted() const { return degree_ >= 0; }
  int degree() const { return degree_; }
  // The fitted functions, as dof * components + component.
  const std::vector<int>& functions() const { return functions_; }
  // Does element k use the shared fit? There, function f equals function twin(f) (an earlier one, with the
  // same coefficients bit for bit) when twin(f) >= 0: the components of a vector space of one element.
  bool shared(int k) const { return slot_[k] < 0; }
  int twin(int f) const { return twin_.empty() ? -1 : twin_[f]; }
  // Monomial coefficients (monomial_count(degree) per function, in functions() order) on element k.
  const double* coefficients(int k) const { return slot_[k] < 0 ? reference_.data() : &own_[slot_[k]]; }
  // The coefficients of each function's derivatives in xi1 then xi2 (monomial_count(degree - 1) each).
  const double* derivative_coefficients(int k) const {
    return slot_[k] < 0 ? reference_derivative_.data()
                        : &own_derivative_[slot_[k] / nm_ * 2 * static_cast<size_t>(monomial_count(degree_ - 1))];
  }

 private:
  void fit(int k, double* coefficients);
  void derive(const std::vector<double>& coefficients, std::vector<double>& derivative) const;
  void check(int k);
  template <int NM>
  void evaluate_fitted(const double* coef, const double* jac, const double* v, const double* d1, const double* d2,
                       double* out) const;
  template <int NM>
  void evaluate_points_fitted(int k, const Point* xi, int n, double* value, double* dx, double* dy) const;
  const Basis& basis_;
  const Mesh& mesh_;
  int degree_, nm_, nc_;
  std::vector<int> functions_;
  std::vector<double> reference_;  // the shared fit
  std::vector<int> twin_;          // per function: an earlier function with the same shared fit, or -1
  std::vector<int> slot_;          // per element: -1 shared fit, else offset in own_
  std::vector<double> own_;        // element fits that differ from the shared one
  std::vector<double> reference_derivative_, own_derivative_;  // derivative_coefficients of both
  std::vector<double> inverse_jacobian_;  // per element: d xi / d x, 4 entries (any basis: to_reference)
  std::vector<double> sample_, check_;
};

}  // namespace dlmfsi
