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
// box of size 0.1 about an image far from the origin and an element of size 0.2 (J of size 5).
TEST(PointMoments3, ElementMomentsAreThePointSumsInTheElementsCoordinates) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const Point3 c{0.3, 0.2, 0.1}, x_c{10.0, -4.0, 2.5};
  const Point3 eta_c{0.25, 0.3, 0.2};
  double j[9];
  for (double& v : j) v = 5 * u(rng);
  std::vector<WeightedPoint> points(37);
  for (WeightedPoint& q : points) {
    q.xi = c + 0.1 * Point3{u(rng), u(rng), u(rng)};
    q.x = x_c + 0.1 * Point3{u(rng), u(rng), u(rng)};
    q.w = 1 + 0.5 * u(rng);
  }
  for (int m = 0; m <= 2; ++m)
    for (int p = 0; p <= 4; ++p) {
      PointMoments3 moments;
      moments.reset(m, p, c, x_c);
      for (const WeightedPoint& q : points) moments.add(q.xi, q.x, q.w);
      moments.settle();
      EXPECT_EQ(moments.points(), static_cast<long>(points.size()));
      std::vector<double> mu(static_cast<size_t>(monomial_count3(m)) * monomial_count3(p));
      moments.element_moments(eta_c, j, mu.data());
      const std::vector<double> expected = direct(points, m, p, c, x_c, eta_c, j);
      double scale = 0;
      for (double v : expected) scale = std::max(scale, std::fabs(v));
      for (size_t i = 0; i < mu.size(); ++i) EXPECT_NEAR(mu[i], expected[i], 1e-14 * scale) << m << " " << p << " " << i;
    }
}

// Points settled in two batches, one set added with the opposite sign, give the difference of the sums.
TEST(PointMoments3, BatchesAndSignsAddUp) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const Point3 c{0, 0, 0}, x_c{1, 1, 1}, eta_c{0.1, 0.2, 0.3};
  const double j[9] = {2, 0.5, 0, -0.3, 1.5, 0.2, 0.1, 0, 3};
  std::vector<WeightedPoint> plus(20), minus(13);
  for (auto* set : {&plus, &minus})
    for (WeightedPoint& q : *set) q = {{u(rng), u(rng), u(rng)}, x_c + Point3{u(rng), u(rng), u(rng)}, 1 + u(rng)};
  PointMoments3 total, part;
  total.reset(1, 2, c, x_c);
  part.reset(1, 2, c, x_c);
  for (int i = 0; i < 10; ++i) part.add(plus[i].xi, plus[i].x, plus[i].w);
  part.settle();
  for (int i = 10; i < 20; ++i) part.add(plus[i].xi, plus[i].x, plus[i].w);
  part.settle();
  total.add(part, 1);
  part.clear();
  for (const WeightedPoint& q : minus) part.add(q.xi, q.x, q.w);
  part.settle();
  total.add(part, -1);
  EXPECT_EQ(total.points(), 33);
  std::vector<double> mu(4 * 10);
  total.element_moments(eta_c, j, mu.data());
  const std::vector<double> a = direct(plus, 1, 2, c, x_c, eta_c, j), b = direct(minus, 1, 2, c, x_c, eta_c, j);
  for (size_t i = 0; i < mu.size(); ++i) EXPECT_NEAR(mu[i], a[i] - b[i], 1e-13 * (std::fabs(a[i]) + std::fabs(b[i])));
}
