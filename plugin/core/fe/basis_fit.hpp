// The functions of a Basis as polynomials in the reference coordinates, element by element (polynomial
// elements on straight triangles): monomial coefficients from interpolation on the degree-d lattice.
// Elements that are affine-equivalent (P0, P1, P1b, P2, P1nc, ...) share one fit, element 0's: each element
// is checked against it with a single basis evaluation at a generic point, and fitted on its own only
// where it differs (e.g. where dof orientation or sign depends on the element).
#pragma once
#include <cstddef>
#include <vector>

#include "fe/basis.hpp"
#include "fe/lattice.hpp"

namespace dlmfsi {

class BasisFit {
 public:
  // The shared fit, on element 0, of the functions that carry the listed components; not fitted() when
  // degree is negative or above kMaxLatticeDegree, or there are no elements.
  BasisFit(const Basis& basis, int elements, int degree, const std::vector<int>& components);
  // The other elements (fitted() only): each checked against the shared fit and fitted on its own where it
  // differs; then the twins and the derivative coefficients.
  void fit_elements(int elements);
  // The shared fit misses the basis (an element that is not polynomial of that degree): not fitted().
  void give_up() { degree_ = -1; }

  bool fitted() const { return degree_ >= 0; }
  int degree() const { return degree_; }
  // monomial_count(degree()), the coefficients per function
  int terms() const { return nm_; }
  // The fitted functions, as dof * components + component.
  const std::vector<int>& functions() const { return functions_; }
  // Does element k use the shared fit? There, function f equals function twin(f) (an earlier one, with the
  // same coefficients bit for bit) when twin(f) >= 0: the components of a vector space of one element.
  bool shared(int k) const { return slot_[k] < 0; }
  void prefetch(int k) const { __builtin_prefetch(&slot_[k]); }
  int twin(int f) const { return twin_.empty() ? -1 : twin_[f]; }
  // Monomial coefficients (monomials() per function, in functions() order) on element k.
  const double* coefficients(int k) const { return slot_[k] < 0 ? reference_.data() : &own_[slot_[k]]; }
  // The coefficients of each function's derivatives in xi1 then xi2 (monomial_count(degree - 1) each).
  const double* derivative_coefficients(int k) const {
    return slot_[k] < 0 ? reference_derivative_.data()
                        : &own_derivative_[slot_[k] / nm_ * 2 * static_cast<size_t>(monomial_count(degree_ - 1))];
  }

 private:
  void fit(int k, double* coefficients);
  void check(int k, const double* v);  // v: the monomials at the check point
  // The rest of check for values in sample_ other than element 0's: the fit's sums, element k's own fit.
  void check_sample(int k, const double* v);
  void derive(const std::vector<double>& coefficients, std::vector<double>& derivative) const;
  const Basis& basis_;
  int degree_, nm_;
  std::vector<int> functions_;
  std::vector<double> reference_;  // the shared fit
  std::vector<int> twin_;          // per function: an earlier function with the same shared fit, or -1
  std::vector<int> slot_;          // per element: -1 shared fit, else offset in own_
  std::vector<double> own_;        // element fits that differ from the shared one
  std::vector<double> reference_derivative_, own_derivative_;  // derivative_coefficients of both
  std::vector<double> sample_;     // room for Basis::values
  std::vector<double> first_values_;  // per function, element 0's value at the check point (empty: not used)
};

}  // namespace dlmfsi
