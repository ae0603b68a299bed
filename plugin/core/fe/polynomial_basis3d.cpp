#include "fe/polynomial_basis3d.hpp"

#include <algorithm>
#include <cmath>

#include "fe/polynomial_fit.hpp"
#include "fe/points_evaluation3d.hpp"

namespace dlmfsi {

namespace {
// A point off every lattice and symmetry plane, where the element check takes place.
constexpr Point3 kCheckPoint{0.2113248654, 0.3141592654, 0.1732050808};
}  // namespace

PolynomialBasis3::PolynomialBasis3(const Basis3& basis, const Mesh3& mesh, int degree, const std::vector<int>& components)
    : basis_(basis),
      frames_(mesh),
      degree_(degree > kMaxLatticeDegree ? -1 : degree),
      nc_(basis.components()),
      functions_(listed_functions(basis, components)) {
  sample_.resize(static_cast<size_t>(basis.local_dofs()) * nc_ * 4);
  check_.resize(sample_.size());
  if (degree_ < 0 || mesh.size() == 0) {
    degree_ = -1;
    return;
  }
  nm_ = monomial_count3(degree_);
  reference_.resize(functions_.size() * nm_);
  fit(0, reference_.data());
  slot_.assign(mesh.size(), -1);
  // Confirm the fit reproduces the basis (values and derivatives) off the lattice.
  if (!fit_reproduces(basis_, {Point3{0.137, 0.291, 0.218}, Point3{0.52, 0.083, 0.171}},
                      [&](Point3 xi, double* out) { evaluate(0, xi, out); }, functions_, sample_.data(),
                      check_.data())) {
    degree_ = -1;
    return;
  }
  twin_ = twin_functions(reference_, nm_);
  terms_.set(degree_, reference_.data(), functions_.size());
  if (degree_ < kMaxLatticeDegree) terms_.prepare_moments();
  // The monomials at the check point, the same for every element; element 0's values there, when its fit
  // gives them: an element whose values there are these bit for bit passes the check as element 0 does,
  // without the fit's sums.
  double v[monomial_count3(kMaxLatticeDegree)];
  monomial_values3(degree_, kCheckPoint, v);
  basis_.values(0, kCheckPoint, sample_.data());
  first_values_.clear();
  if (fit_matches<3>(reference_.data(), nm_, v, functions_, sample_.data()))
    for (int f : functions_) first_values_.push_back(sample_[static_cast<size_t>(f) * Basis3::kSlots]);
  for (int k = 1; k < mesh.size(); ++k) check(k, v);
}

void PolynomialBasis3::fit(int k, double* c) {
  fit_on_lattice(basis_, k, functions_, nm_, vandermonde_inverse3(degree_),
                 [this](int q) { return lattice_point3(degree_, q); },
                 [this](Point3 xi, double* v) { monomial_values3(degree_, xi, v); }, sample_.data(), c);
}

void PolynomialBasis3::check(int k, const double* v) {
  // One evaluation decides whether element k shares the reference fit.
  basis_.values(k, kCheckPoint, sample_.data());
  // element 0's values bit for bit: its check's outcome (passed), without the fit's sums
  if (same_values<3>(sample_.data(), functions_, first_values_) ||
      fit_matches<3>(reference_.data(), nm_, v, functions_, sample_.data()))
    return;
  slot_[k] = static_cast<int>(own_.size());
  own_.resize(own_.size() + functions_.size() * nm_);
  fit(k, &own_[slot_[k]]);
}

void PolynomialBasis3::evaluate_points(int k, const Point3* xi, int n, double* value, double* gradient) const {
  if (shared(k) && !terms_.empty()) {
    terms_.evaluate(twin_.empty() ? nullptr : twin_.data(), inverse_jacobian(k), xi, n, value, gradient);
    return;
  }
  evaluate_polynomials3(degree_, coefficients(k), functions_.size(), nullptr, inverse_jacobian(k), xi, n, value,
                        gradient);
}

void PolynomialBasis3::evaluate_gradient_sums(int k, const Point3* xi, const double* weight, int n, double* value,
                                              double* gradient_sum) const {
  if (shared(k) && !terms_.empty()) {
    terms_.evaluate_gradient_sums(twin_.empty() ? nullptr : twin_.data(), inverse_jacobian(k), xi, weight, n, value,
                                  gradient_sum);
    return;
  }
  evaluate_polynomials3_gradient_sums(degree_, coefficients(k), functions_.size(), inverse_jacobian(k), xi, weight, n,
                                      value, gradient_sum);
}

void PolynomialBasis3::weighted_sums(int k, const Point3* xi, const double* weight, int count, int n,
                                     double* value_sum, double* gradient_sum) const {
  if (shared(k) && !terms_.empty()) {
    terms_.weighted_sums(twin_.empty() ? nullptr : twin_.data(), inverse_jacobian(k), xi, weight, count, n, value_sum,
                         gradient_sum);
    return;
  }
  weighted_sums_polynomials3(degree_, coefficients(k), functions_.size(), inverse_jacobian(k), xi, weight, count, n,
                             value_sum, gradient_sum);
}

void PolynomialBasis3::sums_from_moments(int k, const double* moment, int count, double* value_sum,
                                         double* gradient_sum) const {
  if (shared(k) && !terms_.empty()) {
    terms_.sums_from_moments(twin_.empty() ? nullptr : twin_.data(), inverse_jacobian(k), moment, count, value_sum,
                             gradient_sum);
    return;
  }
  sums_from_moments_polynomials3(degree_, coefficients(k), functions_.size(), inverse_jacobian(k), moment, count,
                                 value_sum, gradient_sum);
}

void PolynomialBasis3::evaluate(int k, Point3 xi, double* out) const {
  if (degree_ < 0) {
    basis_.evaluate(k, xi, out);
    return;
  }
  const size_t width = functions_.size();
  std::vector<double> value(width), gradient(3 * width);
  evaluate_points(k, &xi, 1, value.data(), gradient.data());
  for (size_t f = 0; f < width; ++f) {
    double* o = out + functions_[f] * 4;
    o[0] = value[f];
    o[1] = gradient[3 * f];
    o[2] = gradient[3 * f + 1];
    o[3] = gradient[3 * f + 2];
  }
}

// Degree 1: 4 coefficients per function (monomials 1, xi1, xi2, xi3), the gradient c1 J_1. + c2 J_2. + c3 J_3.;
// degree 0: one, a zero gradient. The sizes and the inverse jacobian are read once (as far as the compiler
// knows the outputs might alias the members); each value is ((c0 + c1 xi1) + c2 xi2) + c3 xi3 and each
// derivative (c1 J_1a + c2 J_2a) + c3 J_3a, in that order.
void PolynomialBasis3::evaluate_affine(int k, Point3 xi, double* value, double* gradient) const {
  const size_t n = functions_.size();
  const double* c = coefficients(k);
  if (nm_ == 1) {
    for (size_t f = 0; f < n; ++f) value[f] = c[f];
    std::fill(gradient, gradient + 3 * n, 0.0);
    return;
  }
  const double* j = inverse_jacobian(k);
  const double j0 = j[0], j1 = j[1], j2 = j[2], j3 = j[3], j4 = j[4], j5 = j[5], j6 = j[6], j7 = j[7], j8 = j[8];
  const double x = xi.x, y = xi.y, z = xi.z;
  for (size_t f = 0; f < n; ++f, c += 4) {
    const double c0 = c[0], c1 = c[1], c2 = c[2], c3 = c[3];
    value[f] = c0 + c1 * x + c2 * y + c3 * z;
    double* g = gradient + 3 * f;
    g[0] = c1 * j0 + c2 * j3 + c3 * j6;
    g[1] = c1 * j1 + c2 * j4 + c3 * j7;
    g[2] = c1 * j2 + c2 * j5 + c3 * j8;
  }
}

void PolynomialBasis3::values_affine(int k, Point3 xi, double* value) const {
  const size_t n = functions_.size();
  const double* c = coefficients(k);
  if (nm_ == 1) {
    for (size_t f = 0; f < n; ++f) value[f] = c[f];
    return;
  }
  const double x = xi.x, y = xi.y, z = xi.z;
  for (size_t f = 0; f < n; ++f, c += 4) value[f] = c[0] + c[1] * x + c[2] * y + c[3] * z;
}

}  // namespace dlmfsi
