// The coefficient certificate of a 2D map's jacobian (jacobian_certainly_positive) against dense sampling:
// wherever it certifies, det dX/dxi >= det A / 4 at every point of a fine lattice (A: the affine interpolant
// of the corner images); it certifies maps near affine and not a map that folds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "errors.hpp"
#include "map/fold.hpp"
#include "fe/lattice.hpp"
#include "map/element_map.hpp"

using namespace dlmfsi;

namespace {

// X = sum over the cubic monomials of the reference coordinates of (cx_m, cy_m).
class CoefficientMap : public SolidMap {
 public:
  CoefficientMap(const double* cx, const double* cy) {
    std::copy(cx, cx + 10, cx_);
    std::copy(cy, cy + 10, cy_);
  }
  int degree() const override { return 3; }
  bool coefficients(int, double* cx, double* cy) const override {
    std::copy(cx_, cx_ + 10, cx);
    std::copy(cy_, cy_ + 10, cy);
    return true;
  }
  MapValue evaluate(int, Point) const override { return MapValue{}; }  // not called: coefficients given

 private:
  double cx_[10], cy_[10];
};

Mesh reference_triangle() {
  Mesh m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}};
  m.triangles = {{0, 1, 2}};
  m.build_adjacency();
  return m;
}

// The smallest det dX/dxi over the degree-60 lattice, relative to det A.
double smallest_relative_det(const TriangleMap& map) {
  const Point a1 = map.corner_image(1) - map.corner_image(0), a2 = map.corner_image(2) - map.corner_image(0);
  const double det_a = cross(a1, a2);
  double smallest = 1e300;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; i + j <= 60; ++j) {
      Point x, d1, d2;
      map.polynomial({i / 60.0, j / 60.0}, x, d1, d2);
      smallest = std::min(smallest, cross(d1, d2) / det_a);
    }
  return smallest;
}

}  // namespace

// Affine part: a rotation and a stretch; the nonlinear coefficients random, of size s.
TEST(Fold, CoefficientCertificateAgainstDenseSampling) {
  const Mesh mesh = reference_triangle();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int certified = 0, not_certified = 0, folding = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const double s = 0.6 * (trial % 20) / 19.0;
    double cx[10] = {0.2, 1.3, -0.4}, cy[10] = {-0.1, 0.5, 0.9};
    for (int m = 3; m < 10; ++m) {
      cx[m] = s * u(rng);
      cy[m] = s * u(rng);
    }
    const CoefficientMap coefficients(cx, cy);
    TriangleMap map;
    map.fit(mesh, coefficients, 0);
    if (jacobian_certainly_positive(map)) {
      ++certified;
      EXPECT_GE(smallest_relative_det(map), 0.25 * (1 - 1e-12)) << "trial " << trial;
    } else {
      ++not_certified;
      if (smallest_relative_det(map) <= 0) ++folding;
    }
  }
  EXPECT_GT(certified, 50);
  EXPECT_GT(folding, 20);  // the sample reaches folds
}

// A map whose first component's derivative in xi1 changes sign inside the triangle (X = (xi1 - 1.2 xi1 xi2,
// xi2), det A = 1, det dX/dxi = 1 - 1.2 xi2): not certified, and check_fold reports the fold.
TEST(Fold, AMapThatFoldsIsNotCertified) {
  const Mesh mesh = reference_triangle();
  double cx[10] = {0, 1, 0, 0, -1.2}, cy[10] = {0, 0, 1};
  const CoefficientMap coefficients(cx, cy);
  TriangleMap map;
  map.fit(mesh, coefficients, 0);
  ASSERT_LT(smallest_relative_det(map), 0);
  EXPECT_FALSE(jacobian_certainly_positive(map));
  EXPECT_THROW(check_fold(map), Error);
}
