#include "map/mapped_element3d.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.hpp"
#include "fe/matrix_inverse.hpp"
#include "geometry/predicates3d.hpp"
#include "map/fold3d.hpp"

namespace dlmfsi {

namespace {

bool finite(Point3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

const Point3 kCorners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

}  // namespace

void MappedTet::prepare(const Mesh3& solid_mesh, const SolidMap3& map, int kk) {
  fit(solid_mesh, map, kk);
  if (!map.corners(k, image))
    for (int i = 0; i < 4; ++i) image[i] = degree_ >= 1 ? at(kCorners[i]).x : map.evaluate(k, kCorners[i]).x;
  for (int i = 0; i < 4; ++i)
    if (!finite(image[i])) throw Error("the map is NaN or Inf at a corner of " + name());
  const int o = orient3d(image[0], image[1], image[2], image[3]);
  if (o == 0) throw Error("the map flattens " + name() + " (its image has zero volume)");
  // (the message formed only when it is thrown: prepare runs for every solid tetrahedron of every call)
  auto inverts = [this] {
    return Error("the map inverts " + name() + " (its image is negatively oriented: a reflection or a fold)");
  };
  if (o < 0 && degree_ == 1) throw inverts();
  const Point3 f1 = image[1] - image[0], f2 = image[2] - image[0], f3 = image[3] - image[0];
  inverse_of_columns(f1, f2, f3, image_inv_);
  if (degree_ == 1) {  // a P1 map: affine by construction
    planar = affine = true;
    nonlinearity = 0;
  } else {
    classify();
    // Corner images negatively oriented: with planar faces the image itself is inverted. A curved map may
    // still be one to one (a sliver whose corners a smooth map moves across the opposite face's chord plane):
    // the fold certificate decides, and the reference side splits what is inverted among its straight images.
    if (o < 0 && (affine || planar)) throw inverts();
    if (!affine) check_fold(*this);
  }
  if (affine) {
    // dX/ds = [image edges] [solid edges]^-1
    const Point3 f[3] = {f1, f2, f3};
    affine_value.x = image[0];
    set_jacobian(f, affine_value);
    affine_det = det3(affine_value.jac);
    if (!(affine_det > 0)) throw Error("the map flattens " + name());
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
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name());
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
  for (int f = 0; f < 4; ++f) {
    const int i0 = (f + 1) % 4, i1 = (f + 2) % 4, i2 = (f + 3) % 4;
    // Planar face: its image points lie on the plane through the face's corner images (a parametrisation
    // within the plane that is not affine is allowed). The normal from edges in units of scale: |n|^2 in the
    // caller's units would be the size to the fourth power, beyond the doubles from about 1e77 (every face then
    // looked planar, and curved maps took the planar path).
    const Point3 n = cross((1 / scale) * (image[i1] - image[i0]), (1 / scale) * (image[i2] - image[i0]));
    const double length = std::sqrt(dot(n, n));
    for (const auto& w : face_weights) {
      const Point3 xi = w[0] * kCorners[i0] + w[1] * kCorners[i1] + w[2] * kCorners[i2];
      const Point3 x = deviation(xi);
      const double off = std::fabs(dot(n, x - image[i0])) / length;
      if (off > tol) planar = false;
    }
  }
  for (Point3 xi : {Point3{0.25, 0.25, 0.25}, Point3{0.1, 0.2, 0.3}, Point3{0.5, 0.15, 0.2}}) deviation(xi);
}

}  // namespace dlmfsi
