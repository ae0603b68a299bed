#include "fe/basis_fit.hpp"

#include "fe/polynomial_fit.hpp"

namespace dlmfsi {

namespace {
// A point off every lattice and symmetry line, where the element check takes place.
constexpr Point kCheckPoint{0.2113248654, 0.3141592654};
}  // namespace

BasisFit::BasisFit(const Basis& basis, int elements, int degree, const std::vector<int>& components)
    : basis_(basis),
      degree_(degree > kMaxLatticeDegree ? -1 : degree),
      nm_(0),
      functions_(listed_functions(basis, components)) {
  sample_.resize(static_cast<size_t>(basis.local_dofs()) * basis.components() * 3);
  if (degree_ < 0 || elements == 0) {
    degree_ = -1;
    return;
  }
  nm_ = monomial_count(degree_);
  reference_.resize(functions_.size() * nm_);
  fit(0, reference_.data());
  slot_.assign(elements, -1);
}

void BasisFit::fit_elements(int elements) {
  // Each function whose shared fit equals an earlier one's is evaluated once, as that one's twin.
  twin_ = twin_functions(reference_, nm_);
  // The monomials at the check point, the same for every element.
  double v[monomial_count(kMaxLatticeDegree)], d1[monomial_count(kMaxLatticeDegree)], d2[monomial_count(kMaxLatticeDegree)];
  monomials(degree_, kCheckPoint, v, d1, d2);
  // Element 0's values at the check point, when its fit gives them: an element whose values there are these
  // bit for bit passes the check as element 0 does, without the fit's sums (check).
  basis_.values(0, kCheckPoint, sample_.data());
  first_values_.clear();
  if (fit_matches<2>(reference_.data(), nm_, v, functions_, sample_.data()))
    for (int f : functions_) first_values_.push_back(sample_[static_cast<size_t>(f) * Basis::kSlots]);
  for (int k = 1; k < elements; ++k) check(k, v);
  derive(reference_, reference_derivative_);
  derive(own_, own_derivative_);
}

void BasisFit::fit(int k, double* c) {
  fit_on_lattice(basis_, k, functions_, nm_, vandermonde_inverse(degree_),
                 [this](int q) { return lattice_point(degree_, q); },
                 [this](Point xi, double* v) { monomial_values(degree_, xi, v); }, sample_.data(), c);
}

void BasisFit::check(int k, const double* v) {
  // One evaluation decides whether element k shares the reference fit.
  basis_.values(k, kCheckPoint, sample_.data());
  // element 0's values bit for bit: its check's outcome (passed), without the fit's sums
  if (!same_values<2>(sample_.data(), functions_, first_values_)) check_sample(k, v);
}

// Not inlined into check, whose code stays short for the elements that give element 0's values.
__attribute__((noinline)) void BasisFit::check_sample(int k, const double* v) {
  if (fit_matches<2>(reference_.data(), nm_, v, functions_, sample_.data())) return;
  slot_[k] = static_cast<int>(own_.size());
  own_.resize(own_.size() + functions_.size() * nm_);
  fit(k, &own_[slot_[k]]);
}

void BasisFit::derive(const std::vector<double>& coefficients, std::vector<double>& derivative) const {
  // d/dxi1 of xi1^a xi2^b is a xi1^(a-1) xi2^b, monomial (t - 1)t/2 + b of degree t - 1 = a + b - 1; likewise
  // d/dxi2 gives b xi1^a xi2^(b-1), monomial (t - 1)t/2 + b - 1.
  const int nm1 = monomial_count(degree_ - 1);
  const size_t count = coefficients.size() / nm_;
  derivative.assign(count * 2 * nm1, 0.0);
  for (size_t f = 0; f < count; ++f) {
    const double* c = &coefficients[f * nm_];
    double* d1 = derivative.data() + f * 2 * nm1;  // empty for degree 0 (no derivative term is written)
    double* d2 = d1 + nm1;
    int m = 0;
    for (int t = 0; t <= degree_; ++t)
      for (int b = 0; b <= t; ++b, ++m) {
        const int a = t - b;
        if (a > 0) d1[(t - 1) * t / 2 + b] += a * c[m];
        if (b > 0) d2[(t - 1) * t / 2 + b - 1] += b * c[m];
      }
  }
}

}  // namespace dlmfsi
