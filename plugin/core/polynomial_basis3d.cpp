#include "polynomial_basis3d.hpp"

#include <algorithm>
#include <cmath>

#include "polynomial_fit.hpp"

namespace dlmfsi {

namespace {
// A point off every lattice and symmetry plane, where the element check takes place.
constexpr Point3 kCheckPoint{0.2113248654, 0.3141592654, 0.1732050808};
}  // namespace

PolynomialBasis3::PolynomialBasis3(const Basis3& basis, const Mesh3& mesh, int degree, const std::vector<int>& components)
    : basis_(basis),
      mesh_(mesh),
      degree_(degree > kMaxLatticeDegree ? -1 : degree),
      nc_(basis.components()),
      functions_(listed_functions(basis, components)) {
  sample_.resize(static_cast<size_t>(basis.local_dofs()) * nc_ * 4);
  check_.resize(sample_.size());
  inverse_jacobian_.resize(9 * static_cast<size_t>(mesh.size()));
  for (int k = 0; k < mesh.size(); ++k) {
    // x = p0 + E xi with E = [e1 e2 e3]: E^-1 has rows (e2 x e3, e3 x e1, e1 x e2) / det E
    Point3 p[4];
    mesh.corners(k, p);
    const Point3 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0];
    const double det = dot(e1, cross(e2, e3));
    const Point3 rows[3] = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
    double* j = &inverse_jacobian_[9 * static_cast<size_t>(k)];
    for (int r = 0; r < 3; ++r) {
      j[3 * r] = rows[r].x / det;
      j[3 * r + 1] = rows[r].y / det;
      j[3 * r + 2] = rows[r].z / det;
    }
  }
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
  for (int k = 1; k < mesh.size(); ++k) check(k);
}

void PolynomialBasis3::fit(int k, double* c) {
  fit_on_lattice(basis_, k, functions_, nm_, vandermonde_inverse3(degree_),
                 [this](int q) { return lattice_point3(degree_, q); }, sample_.data(), c);
}

void PolynomialBasis3::check(int k) {
  // One evaluation decides whether element k shares the reference fit.
  double v[monomial_count3(kMaxLatticeDegree)];
  monomial_values3(degree_, kCheckPoint, v);
  basis_.values(k, kCheckPoint, sample_.data());
  if (fit_matches<3>(reference_.data(), nm_, v, functions_, sample_.data())) return;
  slot_[k] = static_cast<int>(own_.size());
  own_.resize(own_.size() + functions_.size() * nm_);
  fit(k, &own_[slot_[k]]);
}

void PolynomialBasis3::evaluate_points(int k, const Point3* xi, int n, double* value, double* gradient) const {
  const int nm = nm_;
  const size_t width = functions_.size();
  const double* coef = coefficients(k);
  const double* j = inverse_jacobian(k);
  const auto& derivative = monomial_derivatives3(degree_);
  const int nm1 = degree_ > 0 ? monomial_count3(degree_ - 1) : 0;
  // Monomial-major: mono[m * n + p] is monomial m at point p, so that each function's sums run along the
  // points.
  thread_local std::vector<double> scratch, ref;
  if (scratch.size() < static_cast<size_t>(nm) * n) scratch.resize(static_cast<size_t>(nm) * n);
  double* mono = scratch.data();
  for (int p = 0; p < n; ++p) {
    double v[monomial_count3(kMaxLatticeDegree)];
    monomial_values3(degree_, xi[p], v);
    for (int m = 0; m < nm; ++m) mono[static_cast<size_t>(m) * n + p] = v[m];
  }
  if (gradient && ref.size() < 3 * static_cast<size_t>(nm1 > 0 ? nm1 : 1)) ref.resize(3 * static_cast<size_t>(nm1 > 0 ? nm1 : 1));
  const bool twins = shared(k) && !twin_.empty();
  for (size_t f = 0; f < width; ++f) {
    if (twins && twin_[f] >= 0) continue;  // copied below
    const double* c = coef + f * nm;
    double* out = value + f * n;
    for (int p = 0; p < n; ++p) out[p] = c[0];  // monomial 0 is 1
    for (int m = 1; m < nm; ++m) {
      const double cm = c[m];
      const double* row = mono + static_cast<size_t>(m) * n;
      for (int p = 0; p < n; ++p) out[p] += cm * row[p];
    }
    if (!gradient) continue;
    // the reference derivatives' coefficients on the degree - 1 monomials
    double* e = ref.data();
    std::fill(e, e + 3 * nm1, 0.0);
    for (int m = 1; m < nm; ++m)
      for (int i = 0; i < 3; ++i)
        if (derivative[m].index[i] >= 0) e[i * nm1 + derivative[m].index[i]] += derivative[m].factor[i] * c[m];
    double* g[3] = {gradient + (3 * f) * n, gradient + (3 * f + 1) * n, gradient + (3 * f + 2) * n};
    for (int p = 0; p < n; ++p) {
      double r[3] = {0, 0, 0};
      for (int m = 0; m < nm1; ++m) {
        const double mp = mono[static_cast<size_t>(m) * n + p];
        r[0] += e[m] * mp;
        r[1] += e[nm1 + m] * mp;
        r[2] += e[2 * nm1 + m] * mp;
      }
      // d phi / d x_j = sum_i d phi / d xi_i  d xi_i / d x_j
      for (int a = 0; a < 3; ++a) g[a][p] = r[0] * j[a] + r[1] * j[3 + a] + r[2] * j[6 + a];
    }
  }
  if (!twins) return;
  for (size_t f = 0; f < width; ++f) {
    const int t = twin_[f];
    if (t < 0) continue;
    std::copy(value + t * n, value + (t + 1) * n, value + f * n);
    if (gradient) std::copy(gradient + 3 * t * n, gradient + 3 * (t + 1) * n, gradient + 3 * f * n);
  }
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

void PolynomialBasis3::evaluate_affine(int k, Point3 xi, double* value, double* gradient) const {
  const double* c = coefficients(k);
  const double* j = inverse_jacobian(k);
  for (size_t f = 0; f < functions_.size(); ++f, c += nm_) {
    double* g = gradient + 3 * f;
    if (nm_ == 1) {
      value[f] = c[0];
      g[0] = g[1] = g[2] = 0;
      continue;
    }
    // monomials 1, xi1, xi2, xi3
    value[f] = c[0] + c[1] * xi.x + c[2] * xi.y + c[3] * xi.z;
    for (int a = 0; a < 3; ++a) g[a] = c[1] * j[a] + c[2] * j[3 + a] + c[3] * j[6 + a];
  }
}

}  // namespace dlmfsi
