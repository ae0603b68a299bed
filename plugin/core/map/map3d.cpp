#include "map/map3d.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "errors.hpp"
#include "map/map_fold3d.hpp"
#include "geometry/predicates3d.hpp"

namespace dlmfsi {

namespace {

bool finite(Point3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

std::string name(int k) { return "solid tetrahedron " + std::to_string(k); }

// The inverse of the 3 x 3 matrix with columns e1, e2, e3 (rows (e2 x e3, e3 x e1, e1 x e2) / det).
void inverse_of_columns(Point3 e1, Point3 e2, Point3 e3, double inv[3][3]) {
  const double det = dot(e1, cross(e2, e3));
  const Point3 rows[3] = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
  for (int r = 0; r < 3; ++r) {
    inv[r][0] = rows[r].x / det;
    inv[r][1] = rows[r].y / det;
    inv[r][2] = rows[r].z / det;
  }
}

const Point3 kCorners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

}  // namespace

void MappedTet::polynomial(Point3 xi, Point3& x, Point3 d[3]) const {
  const int nm = monomial_count3(degree_);
  double v[monomial_count3(kMaxDegree)];
  monomial_values3(degree_, xi, v);
  double s[3] = {0, 0, 0}, g[3][3] = {};
  const auto& derivative = monomial_derivatives3(degree_);
  for (int m = 0; m < nm; ++m) {
    for (int a = 0; a < 3; ++a) s[a] += c_[a][m] * v[m];
    for (int i = 0; i < 3; ++i) {
      // d/dxi_i of monomial m: factor times monomial j of degree - 1, the first ones of v
      const int j = derivative[m].index[i];
      if (j < 0) continue;
      const double dm = derivative[m].factor[i] * v[j];
      for (int a = 0; a < 3; ++a) g[i][a] += c_[a][m] * dm;
    }
  }
  x = {s[0], s[1], s[2]};
  for (int i = 0; i < 3; ++i) d[i] = {g[i][0], g[i][1], g[i][2]};
}

void MappedTet::set_jacobian(const Point3 d[3], MapValue3& v) const {
  // dX_a/ds_b = sum_i dX_a/dxi_i dxi_i/ds_b
  const double dx[3][3] = {{d[0].x, d[1].x, d[2].x}, {d[0].y, d[1].y, d[2].y}, {d[0].z, d[1].z, d[2].z}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) v.jac[a][b] = dx[a][0] * inv_[0][b] + dx[a][1] * inv_[1][b] + dx[a][2] * inv_[2][b];
}

void MappedTet::reference_derivatives(Point3 xi, Point3& x, Point3 d[3]) const {
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

MapValue3 MappedTet::at(Point3 xi) const {
  if (degree_ < 1) return map_->evaluate(k, xi);
  MapValue3 v;
  Point3 d[3];
  polynomial(xi, v.x, d);
  set_jacobian(d, v);
  return v;
}

void MappedTet::prepare(const Mesh3& solid_mesh, const SolidMap3& map, int kk) {
  k = kk;
  map_ = &map;
  solid_mesh.corners(k, solid);
  const Point3 e1 = solid[1] - solid[0], e2 = solid[2] - solid[0], e3 = solid[3] - solid[0];
  if (orient3d(solid[0], solid[1], solid[2], solid[3]) <= 0)
    throw Error(name(k) + " is flat or negatively oriented in the solid mesh");
  const double det = dot(e1, cross(e2, e3));
  check_tetrahedron_size(det, name(k), "solid");
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
      const auto& inv = vandermonde_inverse3(degree_);
      for (int a = 0; a < 3; ++a)
        for (int m = 0; m < n; ++m) {
          c_[a][m] = 0;
          for (int p = 0; p < n; ++p) c_[a][m] += inv[static_cast<size_t>(m) * n + p] * values[a * n + p];
        }
    }
    for (int a = 0; a < 3; ++a)
      for (int m = 0; m < n; ++m)
        if (!std::isfinite(c_[a][m])) throw Error("the map is NaN or Inf in " + name(k));
  }
  if (!map.corners(k, image))
    for (int i = 0; i < 4; ++i) image[i] = degree_ >= 1 ? at(kCorners[i]).x : map.evaluate(k, kCorners[i]).x;
  for (int i = 0; i < 4; ++i)
    if (!finite(image[i])) throw Error("the map is NaN or Inf at a corner of " + name(k));
  const int o = orient3d(image[0], image[1], image[2], image[3]);
  if (o == 0) throw Error("the map flattens " + name(k) + " (its image has zero volume)");
  if (o < 0) throw Error("the map inverts " + name(k) + " (its image is negatively oriented: a reflection or a fold)");
  const Point3 f1 = image[1] - image[0], f2 = image[2] - image[0], f3 = image[3] - image[0];
  inverse_of_columns(f1, f2, f3, image_inv_);
  if (degree_ == 1) {  // a P1 map: affine by construction
    planar = affine = true;
    nonlinearity = 0;
  } else {
    classify();
    if (!affine) check_fold(*this);
  }
  if (affine) {
    // dX/ds = [image edges] [solid edges]^-1
    const Point3 f[3] = {f1, f2, f3};
    affine_value.x = image[0];
    set_jacobian(f, affine_value);
    affine_det = det3(affine_value.jac);
    if (!(affine_det > 0)) throw Error("the map flattens " + name(k));
  }
}

void MappedTet::classify() {
  // Compare X with the affine interpolant of the corner images at points of the faces and inside. Round-off
  // of the fit and of the map's own evaluation scales with the coordinates, not the tetrahedron.
  double scale = 0, magnitude = 0;
  for (int i = 1; i < 4; ++i) {
    const Point3 e = image[i] - image[0];
    scale += std::fabs(e.x) + std::fabs(e.y) + std::fabs(e.z);
  }
  for (const Point3& p : image) magnitude = std::max({magnitude, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  const double tol = 1e-12 * scale + 1e-14 * magnitude;
  // First from the fitted coefficients: X = F + N, F the terms of degree <= 1 and N the others, each
  // monomial in [0, 1] on the tetrahedron. The affine interpolant of the corner images differs from F by the
  // affine function of corner values image[i] - F(corner i), so at every point |X - interpolant| is at most
  // sum |N's coefficients| + max_i |image[i] - F(corner i)|, component by component. Within tol: affine
  // everywhere (and planar), not only at the samples below.
  if (degree_ >= 2) {
    const int nm = monomial_count3(degree_);
    double bound = 0;  // NaN stays NaN: not decided here
    for (int a = 0; a < 3; ++a) {
      const double* c = c_[a];
      double nonlinear = 0, corner = std::fabs(coordinate(image[0], a) - c[0]);
      for (int m = 4; m < nm; ++m) nonlinear += std::fabs(c[m]);
      for (int i = 1; i < 4; ++i) corner = std::max(corner, std::fabs(coordinate(image[i], a) - (c[0] + c[i])));
      bound += nonlinear + corner;
    }
    if (bound <= tol) {
      planar = affine = true;
      nonlinearity = 0;
      return;
    }
  }
  // Points on the faces (barycentric combinations of three corners) and inside.
  const double face_weights[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.25, 0.25}, {0.2, 0.7, 0.1}, {0.5, 0.5, 0}};
  planar = true;
  affine = true;
  nonlinearity = 0;
  auto deviation = [&](Point3 xi) {
    Point3 x, d[3];
    reference_derivatives(xi, x, d);
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point3 line = from_reference(image, xi);
    const double dev = std::fabs(x.x - line.x) + std::fabs(x.y - line.y) + std::fabs(x.z - line.z);
    if (dev > tol) affine = false;
    // G^-1 dX/dxi - I, G^-1 = image_inv_ (rows: d xi / d y of the affine interpolant)
    for (int r = 0; r < 3; ++r) {
      double row = 0;
      for (int c = 0; c < 3; ++c) {
        const double m = image_inv_[r][0] * d[c].x + image_inv_[r][1] * d[c].y + image_inv_[r][2] * d[c].z;
        row += std::fabs(m - (r == c ? 1 : 0));
      }
      nonlinearity = std::max(nonlinearity, row);
    }
    return x;
  };
  for (int f = 0; f < 4; ++f)
    for (const auto& w : face_weights) {
      const int i0 = (f + 1) % 4, i1 = (f + 2) % 4, i2 = (f + 3) % 4;
      const Point3 xi = w[0] * kCorners[i0] + w[1] * kCorners[i1] + w[2] * kCorners[i2];
      const Point3 x = deviation(xi);
      // Planar face: the image point lies on the plane through the face's corner images (a
      // parametrisation within the plane that is not affine is allowed).
      const Point3 n = cross(image[i1] - image[i0], image[i2] - image[i0]);
      const double off = std::fabs(dot(n, x - image[i0])) / std::sqrt(dot(n, n));
      if (off > tol) planar = false;
    }
  for (Point3 xi : {Point3{0.25, 0.25, 0.25}, Point3{0.1, 0.2, 0.3}, Point3{0.5, 0.15, 0.2}}) deviation(xi);
}

}  // namespace dlmfsi
