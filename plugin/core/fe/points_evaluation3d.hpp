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

  // Weighted sums along the points for count weight vectors at once (weight_k = weight + k n): per function f
  // and k < count, value_sum[count f + k] = sum_p weight_k[p] phi_f(p) and, when gradient_sum is not null,
  // gradient_sum[3 (count f + k) + a] = sum_p weight_k[p] d phi_f / d x_a (p) through j = d xi / d x. Only the
  // weighted sums M_km of the monomials the terms read are formed along the points; each sum is then its
  // constant times M_k0 plus its terms' coefficients times M_km.
  void weighted_sums(const int* twin, const double* j, const Point3* xi, const double* weight, int count, int n,
                     double* value_sum, double* gradient_sum) const;
  // The same sums from the weighted sums of every monomial, moment[k nm + m] = sum_p weight_k[p] (monomial
  // m)(p) (nm = monomial_count3(degree)), however they were formed.
  void sums_from_moments(const int* twin, const double* j, const double* moment, int count, double* value_sum,
                         double* gradient_sum) const;

  // Integrals from moments (integrate_monomials3d.hpp). With M_m = sum_p weight[p] xi^m(p) for the monomials
  // of degree <= degree + 1 (numbered as for that degree), a function's weighted sums are linear in the
  // M_m: sum_p w phi = sum_t c_t M_(m_t), sum_p w xi_k phi = sum_t c_t M_(m_t xi_k), and the derivatives'
  // sums read the M_m of degree - 1. prepare_moments (once, after set) lists the monomials read (0 to 3
  // always: the volume and the centroid) and the rows that form them; moments forms those M_m from n points
  // (the others are left as they are); integrate gives, per function f (twins copied),
  //   first[4 f] = sum_p w phi_f, first[4 f + k] = sum_p w xi_k phi_f (k = 1, 2, 3),
  //   gradient_sum[3 f + a] = sum_p w d phi_f / d x_a (through j = d xi / d x).
  void prepare_moments();
  bool moments_prepared() const { return !moment_list_.empty(); }
  int moment_degree() const { return degree_ + 1; }
  void moments(const Point3* xi, const double* weight, int n, double* moment) const;
  void integrate(const int* twin, const double* j, const double* moment, double* first, double* gradient_sum) const;

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
  // The monomials >= 1 that the terms read, ascending; those the values' terms read, and the rows >= 4 that
  // form them (weighted_sums without the gradients).
  std::vector<int> read_, value_read_, value_rows_;
  // For moments (prepare_moments): the rows >= 4 formed and the monomials whose M_m are read, in the
  // numbering of degree + 1; times_[3 t + k]: monomial_[t] times xi_(k+1) in that numbering.
  std::vector<int> moment_rows_, moment_list_, times_;
};

// The same for one call (the terms formed on the way): a fit used once.
void evaluate_polynomials3(int degree, const double* coef, std::size_t width, const int* twin, const double* j,
                           const Point3* xi, int n, double* value, double* gradient);
// rows[m n + q] = w[q] r_q^m for the monomials m of degree <= degree (lattice3d's order; w null: 1), n points:
// rows 1 to 3 the coordinates, each further one its parent's times one coordinate (monomial_parents3).
void weighted_monomial_rows3(int degree, const Point3* r, const double* w, std::size_t n, double* rows);

void weighted_sums_polynomials3(int degree, const double* coef, std::size_t width, const double* j, const Point3* xi,
                                const double* weight, int count, int n, double* value_sum, double* gradient_sum);
// PolynomialTerms3::sums_from_moments of width polynomials coef (no twins).
void sums_from_moments_polynomials3(int degree, const double* coef, std::size_t width, const double* j,
                                    const double* moment, int count, double* value_sum, double* gradient_sum);
void evaluate_polynomials3_gradient_sums(int degree, const double* coef, std::size_t width, const double* j,
                                         const Point3* xi, const double* weight, int n, double* value,
                                         double* gradient_sum);

}  // namespace dlmfsi
