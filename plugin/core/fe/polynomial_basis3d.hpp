// Fast evaluation of a 3D Basis (the counterpart of polynomial_basis.hpp): on each tetrahedron the basis
// functions are polynomials in the reference coordinates, fitted on the degree-d lattice and evaluated by
// monomials, with physical derivatives through the tetrahedron's affine map. Affine-equivalent elements
// (P0, P1, P1b, P2, ... on every tetrahedron) share one fit: each element is checked against it with a
// single basis evaluation at a generic point, and fitted on its own only where it differs.
#pragma once
#include <cstddef>
#include <vector>

#include "fe/basis.hpp"
#include "fe/lattice3d.hpp"
#include "mesh/mesh3d.hpp"
#include "fe/points_evaluation3d.hpp"
#include "fe/affine_element_maps3d.hpp"

namespace dlmfsi {

class PolynomialBasis3 {
 public:
  // degree: the basis degree on the listed components (polynomial_degree), or -1 to evaluate the basis
  // itself at every point. Only the listed components, on the local dofs that carry them, are computed.
  // If the fit of the first element misses the basis at two points off the lattice (not a polynomial of
  // that degree), every evaluation goes to the basis itself.
  PolynomialBasis3(const Basis3& basis, const Mesh3& mesh, int degree, const std::vector<int>& components);

  bool fitted() const { return degree_ >= 0; }
  int degree() const { return degree_; }
  // The fitted functions, as dof * components + component.
  const std::vector<int>& functions() const { return functions_; }

  // The fitted functions at n points of element k (fitted() only): value[f * n + p] for the f-th of
  // functions() at point p, and when gradient is not null the physical first derivatives
  // gradient[(3 f + i) * n + p], i = x, y, z. Safe to call from several threads.
  void evaluate_points(int k, const Point3* xi, int n, double* value, double* gradient) const;
  // The values as evaluate_points gives them and the gradients' weighted sums along the points,
  // gradient_sum[3 f + i] = sum_p weight[p] d phi_f / d x_i (p) (fitted() only).
  void evaluate_gradient_sums(int k, const Point3* xi, const double* weight, int n, double* value,
                              double* gradient_sum) const;

  // Weighted sums of the fitted functions and of their physical gradients along the points for count weight
  // vectors at once (PolynomialTerms3::weighted_sums; fitted() only).
  void weighted_sums(int k, const Point3* xi, const double* weight, int count, int n, double* value_sum,
                     double* gradient_sum) const;
  // The same sums from the weighted sums of every monomial of degree <= degree() in element k's reference
  // coordinates, moment[k' nm + m] for weight vector k' (PolynomialTerms3::sums_from_moments).
  void sums_from_moments(int k, const double* moment, int count, double* value_sum, double* gradient_sum) const;

  // Integrals from the monomial moments of a piece in element k's reference coordinates
  // (PolynomialTerms3::prepare_moments, integrate): on the elements of the shared fit only.
  bool integrates_moments(int k) const { return shared(k) && terms_.moments_prepared(); }
  int moment_degree() const { return terms_.moment_degree(); }
  void moments(const Point3* xi, const double* weight, int n, double* moment) const {
    terms_.moments(xi, weight, n, moment);
  }
  void integrate_moments(int k, const double* moment, double* first, double* gradient_sum) const {
    terms_.integrate(twin_.empty() ? nullptr : twin_.data(), inverse_jacobian(k), moment, first, gradient_sum);
  }

  // Any basis (fitted or not): Basis3::evaluate's layout for the listed components.
  void evaluate(int k, Point3 xi, double* out) const;

  // Degree 0 or 1 only: the fitted functions' values at xi and their (constant) physical gradients.
  void evaluate_affine(int k, Point3 xi, double* value, double* gradient) const;
  // Degree 0 or 1 only: the values alone (evaluate_affine's, bit for bit).
  void values_affine(int k, Point3 xi, double* value) const;

  // The reference coordinates of x in element k (the inverse of the element's affine map).
  Point3 to_reference(int k, Point3 x) const { return frames_.to_reference(k, x); }
  // The same for x given relative to origin (AffineElementMaps3::to_reference).
  Point3 to_reference(int k, Point3 x_local, Point3 origin) const { return frames_.to_reference(k, x_local, origin); }
  // d xi_i / d x_j of element k, row-major.
  const double* inverse_jacobian(int k) const { return frames_.inverse_jacobian(k); }
  // The point of element k at reference coordinates xi; its edge i (d x / d xi_(i+1)).
  Point3 from_reference(int k, Point3 xi) const { return frames_.from_reference(k, xi); }
  // The same relative to origin (AffineElementMaps3::from_reference).
  Point3 from_reference(int k, Point3 xi, Point3 origin) const { return frames_.from_reference(k, xi, origin); }
  Point3 edge(int k, int i) const { return frames_.edge(k, i); }
  // Does element k use the shared fit (that of element 0)?
  bool shared(int k) const { return slot_[k] < 0; }
  // On elements of the shared fit, function f equals function twin(f) (an earlier one, with the same
  // coefficients bit for bit) when twin(f) >= 0: the components of a vector space of one element.
  int twin(int f) const { return twin_.empty() ? -1 : twin_[f]; }
  // Monomial coefficients (monomial_count3(degree) per function, in functions() order) on element k.
  const double* coefficients(int k) const { return slot_[k] < 0 ? reference_.data() : &own_[slot_[k]]; }

 private:
  void fit(int k, double* coefficients);
  void check(int k, const double* v);  // v: the monomials at the check point
  const Basis3& basis_;
  AffineElementMaps3 frames_;
  int degree_, nm_ = 0, nc_;
  std::vector<int> functions_;
  std::vector<double> reference_;  // the shared fit
  PolynomialTerms3 terms_;         // the shared fit's non-zero terms (empty until it is confirmed)
  std::vector<int> twin_;          // per function: an earlier function with the same shared fit, or -1
  std::vector<int> slot_;          // per element: -1 shared fit, else offset in own_
  std::vector<double> own_;        // element fits that differ from the shared one
  std::vector<double> sample_, check_;
  std::vector<double> first_values_;  // per function, element 0's value at the check point (empty: not used)
};

}  // namespace dlmfsi
