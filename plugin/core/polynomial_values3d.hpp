// Many polynomials on one tetrahedron evaluated at many points, with their physical gradients: the inner
// loop of the 3D bases' evaluation (polynomial_basis3d.hpp).
#pragma once
#include <cstddef>
#include <vector>

#include "point3.hpp"

namespace dlmfsi {

// The width polynomials of one fit (degree 0 to kMaxLatticeDegree, monomial coefficients coef in
// lattice3d.hpp's order, monomial_count3(degree) each) as sums of their non-zero terms: each function's
// value and its three reference derivatives (the derivative polynomials, of degree - 1). A basis such as
// P1b3d's is sparse (its bubble has 4 of the 35 monomials of degree 4, its linear part 4): the sums skip
// the zero terms and are otherwise the dense sums, term by term in the order of the monomials (the same
// values bit for bit from the same monomial values).
class PolynomialTerms3 {
 public:
  PolynomialTerms3() = default;
  PolynomialTerms3(int degree, const double* coef, std::size_t width) { set(degree, coef, width); }
  void set(int degree, const double* coef, std::size_t width);
  bool empty() const { return start_.empty(); }

  // Values value[f * n + p] at the n reference points xi and, when gradient is not null, the physical
  // first derivatives gradient[(3 f + i) * n + p] through j = d xi / d x (row-major). When twin is not
  // null, polynomial f with twin[f] >= 0 is a copy of polynomial twin[f] < f (copied, not computed).
  void evaluate(const int* twin, const double* j, const Point3* xi, int n, double* value, double* gradient) const;
  // The values as above and, instead of the gradients, their weighted sums along the points:
  // gradient_sum[3 f + i] = sum_p weight[p] d phi_f / d x_i (p). With M_m = sum_p weight[p] (monomial m)(p),
  // the sum of a reference derivative is its constant times sum_p weight[p] plus its terms' coefficients
  // times M_m, so the derivatives are never formed at the points.
  void evaluate_gradient_sums(const int* twin, const double* j, const Point3* xi, const double* weight, int n,
                              double* value, double* gradient_sum) const;

 private:
  int degree_ = 0;
  std::size_t width_ = 0;
  // Polynomial r of function f (r = 0 its value, 1 + i its derivative in xi_i): its constant term
  // constant_[4 f + r] and the terms [start_[4 f + r], start_[4 f + r + 1]) of monomial_ / coefficient_,
  // monomials >= 1 in increasing order.
  std::vector<double> constant_;
  std::vector<int> start_, monomial_;
  std::vector<double> coefficient_;
  // The monomial rows >= 4 that evaluate forms (those the terms read and their parents), ascending; the
  // monomials whose weighted sums the derivatives read (0 first).
  std::vector<int> rows_, moments_;
};

// The same for one call (the terms formed on the way): a fit used once.
void evaluate_polynomials3(int degree, const double* coef, std::size_t width, const int* twin, const double* j,
                           const Point3* xi, int n, double* value, double* gradient);
void evaluate_polynomials3_gradient_sums(int degree, const double* coef, std::size_t width, const double* j,
                                         const Point3* xi, const double* weight, int n, double* value,
                                         double* gradient_sum);

}  // namespace dlmfsi
