#include "map/element_map3d.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "errors.hpp"
#include "fe/matrix_inverse.hpp"
#include "geometry/predicates3d.hpp"

namespace dlmfsi {

namespace {

// TetrahedronMap::polynomial's sums for any degree, over the monomials listed in terms (nm of them, ascending:
// those whose coefficients are not all zero; a zero coefficient would add zero).
void sum_polynomial(const double (*c)[monomial_count3(TetrahedronMap::kMaxDegree)], int degree, const int* terms,
                    int nm, Point3 xi, Point3& x, Point3 d[3], int first) {
  double v[monomial_count3(TetrahedronMap::kMaxDegree)];
  monomial_values3(degree, xi, v);
  double s[3] = {0, 0, 0}, g[3][3] = {};
  const MonomialDerivative3* derivative = monomial_derivatives3(degree).data();
  for (int t = 0; t < nm; ++t) {
    const int m = terms[t];
    if (m >= first)
      for (int a = 0; a < 3; ++a) s[a] += c[a][m] * v[m];
    for (int i = 0; i < 3; ++i) {
      // d/dxi_i of monomial m: factor times monomial j of degree - 1, the first ones of v
      const int j = derivative[m].index[i];
      if (j < 0) continue;
      const double dm = derivative[m].factor[i] * v[j];
      for (int a = 0; a < 3; ++a) g[i][a] += c[a][m] * dm;
    }
  }
  x = {s[0], s[1], s[2]};
  for (int i = 0; i < 3; ++i) d[i] = {g[i][0], g[i][1], g[i][2]};
}

// The monomials of degree <= 2 at xi: 1, xi1, xi2, xi3, xi1^2, xi1 xi2, xi2^2, xi1 xi3, xi2 xi3, xi3^2
// (lattice3d.hpp's order).
inline void quadratic_monomials(Point3 xi, double (&v)[10]) {
  v[0] = 1;
  v[1] = xi.x;
  v[2] = xi.y;
  v[3] = xi.z;
  v[4] = xi.x * xi.x;
  v[5] = xi.x * xi.y;
  v[6] = xi.y * xi.y;
  v[7] = xi.x * xi.z;
  v[8] = xi.y * xi.z;
  v[9] = xi.z * xi.z;
}

// sum_m ca[m] v[m] over the ten monomials from monomial first on (0 or 1), in order: the sum starts from the
// constant term (0 + c0 * 1 is c0) and runs a fixed loop after it, unrolled.
inline double quadratic_sum(const double* ca, const double (&v)[10], int first) {
  double sum = first == 0 ? ca[0] : 0.0;
  for (int m = 1; m < 10; ++m) sum += ca[m] * v[m];
  return sum;
}

// The same as sum_polynomial for degree 2 written out, each derivative's terms summed from zero in that order,
// as its loop does.
void sum_quadratic(const double (*c)[monomial_count3(TetrahedronMap::kMaxDegree)], Point3 xi, Point3& x,
                   Point3 d[3], int first) {
  double v[10];
  quadratic_monomials(xi, v);
  const double x2 = 2 * xi.x, y2 = 2 * xi.y, z2 = 2 * xi.z;
  double s[3], g[3][3];
  for (int a = 0; a < 3; ++a) {
    const double* ca = c[a];
    s[a] = quadratic_sum(ca, v, first);
    g[0][a] = ca[1] + ca[4] * x2 + ca[5] * xi.y + ca[7] * xi.z;  // d/dxi1: xi1, xi1^2, xi1 xi2, xi1 xi3
    g[1][a] = ca[2] + ca[5] * xi.x + ca[6] * y2 + ca[8] * xi.z;  // d/dxi2: xi2, xi1 xi2, xi2^2, xi2 xi3
    g[2][a] = ca[3] + ca[7] * xi.x + ca[8] * xi.y + ca[9] * z2;  // d/dxi3: xi3, xi1 xi3, xi2 xi3, xi3^2
  }
  x = {s[0], s[1], s[2]};
  for (int i = 0; i < 3; ++i) d[i] = {g[i][0], g[i][1], g[i][2]};
}

}  // namespace

void TetrahedronMap::polynomial(Point3 xi, Point3& x, Point3 d[3], int first) const {
  if (degree_ == 2)  // P23d maps, whose Newton pull-backs call this at every point of a curved piece
    sum_quadratic(c_, xi, x, d, first);
  else
    sum_polynomial(c_, degree_, terms_, term_count_, xi, x, d, first);
}

Point3 TetrahedronMap::polynomial_value(Point3 xi, int first) const {
  double s[3];
  if (degree_ == 2) {  // sum_quadratic's sums
    double v[10];
    quadratic_monomials(xi, v);
    return {quadratic_sum(c_[0], v, first), quadratic_sum(c_[1], v, first), quadratic_sum(c_[2], v, first)};
  }
  double v[monomial_count3(kMaxDegree)];
  monomial_values3(degree_, xi, v);
  for (int a = 0; a < 3; ++a) {
    double sum = 0;
    for (int t = 0; t < term_count_; ++t)
      if (terms_[t] >= first) sum += c_[a][terms_[t]] * v[terms_[t]];
    s[a] = sum;
  }
  return {s[0], s[1], s[2]};
}

Point3 TetrahedronMap::position(Point3 xi) const {
  if (degree_ >= 1) return polynomial_value(xi, 0);
  return map_->evaluate(k, xi).x;
}

bool TetrahedronMap::reference_hessian(double h[3][3][3]) const {
  if (degree_ != 2) return false;
  for (int a = 0; a < 3; ++a) {  // monomials xi1^2, xi1 xi2, xi2^2, xi1 xi3, xi2 xi3, xi3^2: c_[a][4 .. 9]
    const double* ca = c_[a];
    h[a][0][0] = 2 * ca[4];
    h[a][1][1] = 2 * ca[6];
    h[a][2][2] = 2 * ca[9];
    h[a][0][1] = h[a][1][0] = ca[5];
    h[a][0][2] = h[a][2][0] = ca[7];
    h[a][1][2] = h[a][2][1] = ca[8];
  }
  return true;
}

void TetrahedronMap::set_jacobian(const Point3 d[3], MapValue3& v) const {
  // dX_a/ds_b = sum_i dX_a/dxi_i dxi_i/ds_b
  const double dx[3][3] = {{d[0].x, d[1].x, d[2].x}, {d[0].y, d[1].y, d[2].y}, {d[0].z, d[1].z, d[2].z}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) v.jac[a][b] = dx[a][0] * inv_[0][b] + dx[a][1] * inv_[1][b] + dx[a][2] * inv_[2][b];
}

void TetrahedronMap::reference_derivatives(Point3 xi, Point3& x, Point3 d[3]) const {
  if (degree_ >= 1) {
    polynomial(xi, x, d);
    return;
  }
  // dX/dxi_i = dX/ds e_i
  const MapValue3 v = map_->evaluate(k, xi);
  x = v.x;
  const Point3 e[3] = {solid[1] - solid[0], solid[2] - solid[0], solid[3] - solid[0]};
  for (int i = 0; i < 3; ++i)
    d[i] = {v.jac[0][0] * e[i].x + v.jac[0][1] * e[i].y + v.jac[0][2] * e[i].z,
            v.jac[1][0] * e[i].x + v.jac[1][1] * e[i].y + v.jac[1][2] * e[i].z,
            v.jac[2][0] * e[i].x + v.jac[2][1] * e[i].y + v.jac[2][2] * e[i].z};
}

MapValue3 TetrahedronMap::at(Point3 xi) const {
  if (degree_ < 1) return map_->evaluate(k, xi);
  MapValue3 v;
  Point3 d[3];
  polynomial(xi, v.x, d);
  set_jacobian(d, v);
  return v;
}

void TetrahedronMap::fit(const Mesh3& solid_mesh, const SolidMap3& map, int kk) {
  k = kk;
  map_ = &map;
  solid_mesh.corners(k, solid);
  const Point3 e1 = solid[1] - solid[0], e2 = solid[2] - solid[0], e3 = solid[3] - solid[0];
  if (orient3d(solid[0], solid[1], solid[2], solid[3]) <= 0)
    throw Error(name() + " is flat or negatively oriented in the solid mesh");
  const double det = dot(e1, cross(e2, e3));
  check_tetrahedron_size(det, k, "solid");
  inverse_of_columns(e1, e2, e3, inv_);

  degree_ = map.degree();
  if (degree_ > kMaxDegree) degree_ = -1;
  if (degree_ >= 1) {
    const int n = monomial_count3(degree_);
    if (!map.coefficients(k, c_[0], c_[1], c_[2])) {
      std::vector<double> values(3 * static_cast<size_t>(n));
      for (int p = 0; p < n; ++p) {
        const Point3 x = map.evaluate(k, lattice_point3(degree_, p)).x;
        values[p] = x.x;
        values[n + p] = x.y;
        values[2 * n + p] = x.z;
      }
      // relative to the first lattice point's value (V^-1's rows add up to e_0), as in 2D
      const auto& inv = vandermonde_inverse3(degree_);
      for (int a = 0; a < 3; ++a) {
        const double v0 = values[a * n];
        for (int m = 0; m < n; ++m) {
          c_[a][m] = 0;
          for (int p = 1; p < n; ++p) c_[a][m] += inv[static_cast<size_t>(m) * n + p] * (values[a * n + p] - v0);
        }
        c_[a][0] += v0;
      }
    }
    for (int a = 0; a < 3; ++a)
      for (int m = 0; m < n; ++m)
        if (!std::isfinite(c_[a][m])) throw Error("the map is NaN or Inf in " + name());
  }
  term_count_ = 0;
  for (int m = 0; m < (degree_ >= 1 ? monomial_count3(degree_) : 0); ++m)
    if (c_[0][m] != 0 || c_[1][m] != 0 || c_[2][m] != 0) terms_[term_count_++] = m;
  detect_bubble();
}

void TetrahedronMap::detect_bubble() {
  bubble_ = false;
  if (degree_ < 4) return;
  const int n = monomial_count3(degree_), m111 = monomial_index3(1, 1, 1);
  const int minus[3] = {monomial_index3(2, 1, 1), monomial_index3(1, 2, 1), monomial_index3(1, 1, 2)};
  double beta[3];
  bool any = false;
  for (int a = 0; a < 3; ++a) {
    const double* c = c_[a];
    beta[a] = c[m111];
    const double tolerance = 1e-6 * (std::fabs(c[1]) + std::fabs(c[2]) + std::fabs(c[3]) + std::fabs(beta[a]));
    for (int m = 4; m < n; ++m) {
      const double expected = m == m111 ? beta[a] : (m == minus[0] || m == minus[1] || m == minus[2]) ? -beta[a] : 0;
      if (!(std::fabs(c[m] - expected) <= tolerance)) return;
    }
    any = any || beta[a] != 0;
  }
  if (!any) return;  // affine: the affine path
  const Point3 d1 = bubble_linear(0), d2 = bubble_linear(1), d3 = bubble_linear(2);
  if (!(dot(d1, cross(d2, d3)) > 0)) return;  // Newton's path reports what is wrong
  inverse_of_columns(d1, d2, d3, bubble_inv_);
  bubble_beta_ = {beta[0], beta[1], beta[2]};
  bubble_v_ = bubble_linear_inverse(bubble_beta_);
  bubble_ = true;
}

}  // namespace dlmfsi
