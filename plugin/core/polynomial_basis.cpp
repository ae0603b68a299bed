#include "polynomial_basis.hpp"

#include <algorithm>
#include <cmath>

#include "lattice.hpp"
#include "polynomial_fit.hpp"

namespace dlmfsi {

namespace {
// A point off every lattice and symmetry line, where the element check takes place.
constexpr Point kCheckPoint{0.2113248654, 0.3141592654};
}  // namespace

PolynomialBasis::PolynomialBasis(const Basis& basis, const Mesh& mesh, int degree, const std::vector<int>& components)
    : basis_(basis),
      mesh_(mesh),
      degree_(degree > kMaxLatticeDegree ? -1 : degree),
      nm_(0),
      nc_(basis.components()),
      functions_(listed_functions(basis, components)) {
  sample_.resize(static_cast<size_t>(basis.local_dofs()) * nc_ * 3);
  check_.resize(sample_.size());
  inverse_jacobian_.resize(4 * static_cast<size_t>(mesh.size()));
  for (int k = 0; k < mesh.size(); ++k) {
    // d xi / d x for x = p0 + xi1 e1 + xi2 e2
    Point p[3];
    mesh_.corners(k, p);
    const Point e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double det = cross(e1, e2);
    double* j = &inverse_jacobian_[4 * static_cast<size_t>(k)];
    j[0] = e2.y / det;
    j[1] = -e2.x / det;
    j[2] = -e1.y / det;
    j[3] = e1.x / det;
  }
  if (degree_ < 0 || mesh.size() == 0) {
    degree_ = -1;
    return;
  }
  nm_ = monomial_count(degree_);
  reference_.resize(functions_.size() * nm_);
  fit(0, reference_.data());
  slot_.assign(mesh.size(), -1);
  // Confirm the fit reproduces the basis (values and derivatives) off the lattice.
  if (!fit_reproduces(basis_, {Point{0.137, 0.291}, Point{0.52, 0.083}},
                      [&](Point xi, double* out) { evaluate(0, xi, out); }, functions_, sample_.data(), check_.data())) {
    degree_ = -1;
    return;
  }
  // Each function whose shared fit equals an earlier one's is evaluated once, as that one's twin.
  twin_ = twin_functions(reference_, nm_);
  for (int k = 1; k < mesh.size(); ++k) check(k);
  derive(reference_, reference_derivative_);
  derive(own_, own_derivative_);
}

void PolynomialBasis::derive(const std::vector<double>& coefficients, std::vector<double>& derivative) const {
  // d/dxi1 of xi1^a xi2^b is a xi1^(a-1) xi2^b, monomial (t - 1)t/2 + b of degree t - 1 = a + b - 1; likewise
  // d/dxi2 gives b xi1^a xi2^(b-1), monomial (t - 1)t/2 + b - 1.
  const int nm1 = monomial_count(degree_ - 1);
  const size_t count = coefficients.size() / nm_;
  derivative.assign(count * 2 * nm1, 0.0);
  for (size_t f = 0; f < count; ++f) {
    const double* c = &coefficients[f * nm_];
    double* d1 = &derivative[f * 2 * nm1];
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

void PolynomialBasis::fit(int k, double* c) {
  fit_on_lattice(basis_, k, functions_, nm_, vandermonde_inverse(degree_),
                 [this](int q) { return lattice_point(degree_, q); }, sample_.data(), c);
}

void PolynomialBasis::check(int k) {
  // One evaluation decides whether element k shares the reference fit.
  double v[monomial_count(kMaxLatticeDegree)], d1[monomial_count(kMaxLatticeDegree)], d2[monomial_count(kMaxLatticeDegree)];
  monomials(degree_, kCheckPoint, v, d1, d2);
  basis_.values(k, kCheckPoint, sample_.data());
  if (fit_matches<2>(reference_.data(), nm_, v, functions_, sample_.data())) return;
  slot_[k] = static_cast<int>(own_.size());
  own_.resize(own_.size() + functions_.size() * nm_);
  fit(k, &own_[slot_[k]]);
}

template <int NM>
void PolynomialBasis::evaluate_fitted(const double* coef, const double* j, const double* v, const double* d1,
                                      const double* d2, double* out) const {
  const int nm = NM > 0 ? NM : nm_;
  for (int f : functions_) {
    double val = 0, g1 = 0, g2 = 0;
    for (int m = 0; m < nm; ++m) {
      val += coef[m] * v[m];
      g1 += coef[m] * d1[m];
      g2 += coef[m] * d2[m];
    }
    coef += nm;
    double* o = out + f * 3;
    o[0] = val;
    o[1] = g1 * j[0] + g2 * j[2];
    o[2] = g1 * j[1] + g2 * j[3];
  }
}

void PolynomialBasis::evaluate(int k, Point xi, double* out) const {
  if (degree_ < 0) {
    basis_.evaluate(k, xi, out);
    return;
  }
  const double* coef = coefficients(k);
  const double* j = &inverse_jacobian_[4 * static_cast<size_t>(k)];
  double v[monomial_count(kMaxLatticeDegree)], d1[monomial_count(kMaxLatticeDegree)], d2[monomial_count(kMaxLatticeDegree)];
  monomials(degree_, xi, v, d1, d2);
  // Fixed trip counts for the common degrees let the compiler unroll the sums.
  switch (degree_) {
    case 1: evaluate_fitted<3>(coef, j, v, d1, d2, out); break;
    case 2: evaluate_fitted<6>(coef, j, v, d1, d2, out); break;
    case 3: evaluate_fitted<10>(coef, j, v, d1, d2, out); break;
    default: evaluate_fitted<0>(coef, j, v, d1, d2, out); break;
  }
}

template <int NM>
void PolynomialBasis::evaluate_points_fitted(int k, const Point* xi, int n, double* value, double* dx,
                                             double* dy) const {
  // Monomial-major: mono[m * n + p] is monomial m at point p, so that each function's sums run along the
  // points (vectorizable); the derivatives come from the derivative polynomials' coefficients (degree - 1).
  constexpr int kDegree = NM == 1 ? 0 : NM == 3 ? 1 : NM == 6 ? 2 : NM == 10 ? 3 : -1;
  const int degree = kDegree >= 0 ? kDegree : degree_;
  const int nm = NM > 0 ? NM : nm_;
  const int nm1 = monomial_count(degree - 1);
  const size_t width = functions_.size();
  const double* coef = coefficients(k);
  const double* deriv = derivative_coefficients(k);
  const double* j = &inverse_jacobian_[4 * static_cast<size_t>(k)];
  const bool shared = slot_[k] < 0;
  thread_local std::vector<double> scratch;
  if (scratch.size() < static_cast<size_t>(nm) * n) scratch.resize(static_cast<size_t>(nm) * n);
  double* mono = scratch.data();
  for (int p = 0; p < n; ++p) {
    double v[monomial_count(kMaxLatticeDegree)];
    monomial_values(degree, xi[p], v);
    for (int m = 0; m < nm; ++m) mono[static_cast<size_t>(m) * n + p] = v[m];
  }
  for (size_t f = 0; f < width; ++f) {
    if (shared && twin_[f] >= 0) continue;
    const double* c = coef + f * nm;
    double* out = value + f * n;
    for (int p = 0; p < n; ++p) out[p] = c[0];  // monomial 0 is 1
    for (int m = 1; m < nm; ++m) {
      const double cm = c[m];
      const double* row = mono + static_cast<size_t>(m) * n;
      for (int p = 0; p < n; ++p) out[p] += cm * row[p];
    }
    if (!dx) continue;
    const double *e1 = deriv + f * 2 * nm1, *e2 = e1 + nm1;
    double *gx = dx + f * n, *gy = dy + f * n;
    for (int p = 0; p < n; ++p) {
      double g1 = 0, g2 = 0;
      for (int m = 0; m < nm1; ++m) {
        g1 += e1[m] * mono[static_cast<size_t>(m) * n + p];
        g2 += e2[m] * mono[static_cast<size_t>(m) * n + p];
      }
      gx[p] = g1 * j[0] + g2 * j[2];
      gy[p] = g1 * j[1] + g2 * j[3];
    }
  }
  // the twins' rows: copies of the rows they repeat
  if (!shared) return;
  for (size_t f = 0; f < width; ++f)
    if (twin_[f] >= 0)
      for (double* plane : {value, dx, dy})
        if (plane) std::copy(plane + twin_[f] * n, plane + (twin_[f] + 1) * n, plane + f * n);
}

void PolynomialBasis::evaluate_points(int k, const Point* xi, int n, double* value, double* dx, double* dy) const {
  switch (degree_) {
    case 0: evaluate_points_fitted<1>(k, xi, n, value, dx, dy); break;
    case 1: evaluate_points_fitted<3>(k, xi, n, value, dx, dy); break;
    case 2: evaluate_points_fitted<6>(k, xi, n, value, dx, dy); break;
    case 3: evaluate_points_fitted<10>(k, xi, n, value, dx, dy); break;
    default: evaluate_points_fitted<0>(k, xi, n, value, dx, dy); break;
  }
}

}  // namespace dlmfsi
