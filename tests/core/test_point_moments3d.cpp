// PointMoments3: moments of weighted points in the image's coordinates carried to an element's reference
// coordinates, against the sums formed point by point in those coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "fe/lattice3d.hpp"
#include "integration/point_moments3d.hpp"

using namespace dlmfsi;

namespace {

struct WeightedPoint {
  Point3 xi, x;
  double w;
};

// sum_q w (xi - c)^g eta^a, eta = eta_c + J (x - x_c), monomial by monomial at each point.
std::vector<double> direct(const std::vector<WeightedPoint>& points, int m, int p, Point3 c, Point3 x_c, Point3 eta_c,
                           const double (&j)[9]) {
  const int cg = monomial_count3(m), cb = monomial_count3(p);
  std::vector<double> out(static_cast<size_t>(cg) * cb, 0.0);
  for (const WeightedPoint& q : points) {
    const Point3 r = q.x - x_c;
    const Point3 eta{eta_c.x + j[0] * r.x + j[1] * r.y + j[2] * r.z, eta_c.y + j[3] * r.x + j[4] * r.y + j[5] * r.z,
                     eta_c.z + j[6] * r.x + j[7] * r.y + j[8] * r.z};
    double g[monomial_count3(kMaxLatticeDegree)], a[monomial_count3(kMaxLatticeDegree)];
    monomial_values3(m, q.xi - c, g);
    monomial_values3(p, eta, a);
    for (int k = 0; k < cg; ++k)
      for (int b = 0; b < cb; ++b) out[k * cb + b] += q.w * g[k] * a[b];
  }
  return out;
}

}  // namespace

// Every multiplier degree the weighted sums take (0 to 2) against fluid degrees 0 to 4, points spread over a
// box of size 0.1 about an image far from the origin and an element of size 0.2 (J of size 5), settled in two
// batches.
TEST(PointMoments3, ElementMomentsAreThePointSumsInTheElementsCoordinates) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const Point3 c{0.3, 0.2, 0.1}, centre{10.0, -4.0, 2.5};
  const Point3 eta_centre{0.25, 0.3, 0.2};  // eta at centre
  double j[9];
  for (double& v : j) v = 5 * u(rng);
  std::vector<WeightedPoint> points(37);
  for (WeightedPoint& q : points) {
    q.xi = c + 0.1 * Point3{u(rng), u(rng), u(rng)};
    q.x = centre + 0.1 * Point3{u(rng), u(rng), u(rng)};
    q.w = 1 + 0.5 * u(rng);
  }
  for (int m = 0; m <= 2; ++m)
    for (int p = 0; p <= 4; ++p) {
      PointMoments3 moments;
      moments.reset(m, p, c);
      for (size_t i = 0; i < points.size(); ++i) {
        moments.add(points[i].xi, points[i].x, points[i].w);
        if (i == 10) moments.settle();
      }
      moments.settle();
      EXPECT_EQ(moments.points(), static_cast<long>(points.size()));
      const Point3 r = moments.x_centre() - centre;  // eta at the moments' x centre
      const Point3 eta_c{eta_centre.x + j[0] * r.x + j[1] * r.y + j[2] * r.z,
                         eta_centre.y + j[3] * r.x + j[4] * r.y + j[5] * r.z,
                         eta_centre.z + j[6] * r.x + j[7] * r.y + j[8] * r.z};
      std::vector<double> mu(static_cast<size_t>(monomial_count3(m)) * monomial_count3(p));
      moments.element_moments(eta_c, j, mu.data());
      const std::vector<double> expected = direct(points, m, p, c, centre, eta_centre, j);
      double scale = 0;
      for (double v : expected) scale = std::max(scale, std::fabs(v));
      for (size_t i = 0; i < mu.size(); ++i)
        EXPECT_NEAR(mu[i], expected[i], 1e-13 * scale) << m << " " << p << " " << i;
    }
}

// clear() empties the moments, the next points' mean the x centre.
TEST(PointMoments3, ClearStartsAfresh) {
  const double j[9] = {2, 0.5, 0, -0.3, 1.5, 0.2, 0.1, 0, 3};
  PointMoments3 moments;
  moments.reset(1, 2, {0, 0, 0});
  moments.add({1, 2, 3}, {4, 5, 6}, 7);
  moments.settle();
  moments.clear();
  EXPECT_EQ(moments.points(), 0);
  const WeightedPoint q{{0.1, 0.2, 0.3}, {1, 1, 1}, 2};
  moments.add(q.xi, q.x, q.w);
  moments.settle();
  EXPECT_EQ(moments.points(), 1);
  std::vector<double> mu(4 * 10);
  moments.element_moments({0.1, 0.2, 0.3}, j, mu.data());
  const std::vector<double> expected = direct({q}, 1, 2, {0, 0, 0}, q.x, {0.1, 0.2, 0.3}, j);
  for (size_t i = 0; i < mu.size(); ++i) EXPECT_NEAR(mu[i], expected[i], 1e-15) << i;
}

// The mesh's units do not matter: the same points in units of 1e-95 (x, and J by 1e95) and weights of 1e-285 (a
// solid tetrahedron's measure in those units) give the moments times 1e-285, not underflow (r^b with r of size
// 1e-95 and b up to 4 is below the doubles).
TEST(PointMoments3, UnitsOfTheMeshDoNotMatter) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  double j[9], j_small[9];
  for (int i = 0; i < 9; ++i) {
    j[i] = 3 * u(rng);
    j_small[i] = j[i] * 1e95;
  }
  PointMoments3 unit, small;
  unit.reset(2, 4, {0.1, 0.1, 0.1});
  small.reset(2, 4, {0.1, 0.1, 0.1});
  for (int q = 0; q < 25; ++q) {
    const Point3 xi{u(rng), u(rng), u(rng)}, x{1 + 0.2 * u(rng), 2 + 0.2 * u(rng), 0.2 * u(rng)};
    const double w = 1 + 0.5 * u(rng);
    unit.add(xi, x, w);
    small.add(xi, 1e-95 * x, 1e-285 * w);
  }
  unit.settle();
  small.settle();
  const Point3 eta_c{0.2, 0.3, 0.1};
  std::vector<double> a(10 * 35), b(10 * 35);
  unit.element_moments(eta_c, j, a.data());
  small.element_moments(eta_c, j_small, b.data());
  double scale = 0;
  for (double v : a) scale = std::max(scale, std::fabs(v));
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(b[i] * 1e285, a[i], 1e-13 * scale) << i;
}
