// conic_region_rule: areas and moments of regions bounded by conics inside convex polygons, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "integration/conic_region.hpp"

using namespace dlmfsi;

namespace {

struct Moments {
  double area = 0, x = 0, xx = 0, xy4 = 0;  // 1, u, u^2, u^2 v^2
};

Moments integrate(std::vector<std::array<double, 2>> polygon, const Quadratic2& q, int sign, int degree = 20) {
  std::vector<RegionPoint2> points;
  double p[16][2];
  for (size_t i = 0; i < polygon.size(); ++i) {
    p[i][0] = polygon[i][0];
    p[i][1] = polygon[i][1];
  }
  conic_region_rule(p, static_cast<int>(polygon.size()), q, sign, line_rule(degree), line_rule(degree), points);
  Moments m;
  for (const RegionPoint2& r : points) {
    m.area += r.weight;
    m.x += r.weight * r.u;
    m.xx += r.weight * r.u * r.u;
    m.xy4 += r.weight * r.u * r.u * r.v * r.v;
  }
  return m;
}

// q = r^2 - (u - cu)^2 - (v - cv)^2: positive inside the disk.
Quadratic2 disk(double cu, double cv, double r) {
  Quadratic2 q;
  q.c0 = r * r - cu * cu - cv * cv;
  q.cu = 2 * cu;
  q.cv = 2 * cv;
  q.cuu = -1;
  q.cvv = -1;
  return q;
}

const double kPi = 3.14159265358979323846;

}  // namespace

// A disk strictly inside a square: the curve has two tangents along any direction inside the polygon, and
// no crossing of an edge.
TEST(ConicRegion, DiskInsideASquare) {
  const double r = 0.7;
  for (int degree : {10, 20}) {  // a band's degree, and more
  const Moments m = integrate({{{-1, -1}}, {{1, -1}}, {{1, 1}}, {{-1, 1}}}, disk(0, 0, r), 1, degree);
  EXPECT_NEAR(m.area, kPi * r * r, 1e-14);
  EXPECT_NEAR(m.x, 0, 1e-15);
  EXPECT_NEAR(m.xx, kPi * std::pow(r, 4) / 4, 1e-14);
  EXPECT_NEAR(m.xy4, kPi * std::pow(r, 6) / 24, 1e-14);
  }
}

// A disk cut by an edge of the polygon (y >= d): the circular segment, r^2 acos(d / r) - d sqrt(r^2 - d^2), and
// the rest of the rectangle with the opposite sign.
TEST(ConicRegion, CircularSegment) {
  const double r = 0.8, d = 0.3;
  const std::vector<std::array<double, 2>> box = {{{-2, d}}, {{2, d}}, {{2, 2}}, {{-2, 2}}};
  const double segment = r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d);
  const Moments in = integrate(box, disk(0, 0, r), 1), out = integrate(box, disk(0, 0, r), -1);
  EXPECT_NEAR(in.area, segment, 1e-14);
  EXPECT_NEAR(out.area, 4 * (2 - d) - segment, 1e-13);
}

// A hyperbola: u v > 1/10 on the unit square, 0.9 - ln(10) / 10.
TEST(ConicRegion, Hyperbola) {
  Quadratic2 q;
  q.c0 = -0.1;
  q.cuv = 1;
  const Moments m = integrate({{{0, 0}}, {{1, 0}}, {{1, 1}}, {{0, 1}}}, q, 1);
  EXPECT_NEAR(m.area, 0.9 - std::log(10.0) / 10, 1e-14);
}

// Two crossing lines (u^2 - v^2, whose gradient vanishes at the crossing): |u| > |v| is half the square.
TEST(ConicRegion, CrossingLines) {
  Quadratic2 q;
  q.cuu = 1;
  q.cvv = -1;
  const std::vector<std::array<double, 2>> square = {{{-1, -1}}, {{1, -1}}, {{1, 1}}, {{-1, 1}}};
  EXPECT_NEAR(integrate(square, q, 1).area, 2, 1e-14);
  EXPECT_NEAR(integrate(square, q, -1).area, 2, 1e-14);
}

// Tilted ellipses 1 - (x / A)^2 - (y / B)^2 > 0 in axes turned by theta, inside a hexagon: pi A B; the second
// two hundred times longer than wide, whose coefficients' round-off alone moves its area by about (A / B)^2 eps
// (its determinant is a difference of terms 4e4 times larger): a tolerance of 1e-11 there.
TEST(ConicRegion, TiltedEllipses) {
  std::vector<std::array<double, 2>> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.push_back({{3 * std::cos(k * kPi / 3 + 0.1), 3 * std::sin(k * kPi / 3 + 0.1)}});
  for (const std::array<double, 4>& e :
       {std::array<double, 4>{1.2, 0.7, 0.4, 1e-14}, std::array<double, 4>{2.5, 0.0125, 0.3, 1e-11}}) {
    const double a = e[0], b = e[1], c = std::cos(e[2]), s = std::sin(e[2]);
    Quadratic2 q;  // x = c u + s v, y = -s u + c v
    q.c0 = 1;
    q.cuu = -(c * c / (a * a) + s * s / (b * b));
    q.cuv = -2 * c * s * (1 / (a * a) - 1 / (b * b));
    q.cvv = -(s * s / (a * a) + c * c / (b * b));
    EXPECT_NEAR(integrate(hexagon, q, 1).area / (kPi * a * b), 1, e[3]);
    EXPECT_NEAR(integrate(hexagon, q, 1, 10).area / (kPi * a * b), 1, e[3]);  // the lower degree of a band
  }
}

// A line (q affine): the polygon's part on one side, exactly.
TEST(ConicRegion, HalfPlane) {
  Quadratic2 q;
  q.c0 = -0.25;
  q.cu = 1;
  q.cv = 0.5;
  // the triangle (0,0), (1,0), (0,1) where u + v / 2 > 1/4: the triangle less (0,0), (1/4,0), (0,1/2)
  EXPECT_NEAR(integrate({{{0, 0}}, {{1, 0}}, {{0, 1}}}, q, 1).area, 0.5 - 1.0 / 16, 1e-15);
}

// Nothing where the sign never holds, and the whole polygon where it always does.
TEST(ConicRegion, EmptyAndWhole) {
  const std::vector<std::array<double, 2>> square = {{{-1, -1}}, {{1, -1}}, {{1, 1}}, {{-1, 1}}};
  EXPECT_EQ(integrate(square, disk(5, 5, 1), 1).area, 0);
  EXPECT_NEAR(integrate(square, disk(5, 5, 1), -1).area, 4, 1e-14);
}
