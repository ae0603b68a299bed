// conic_region_rule: areas and moments of regions bounded by conics inside convex polygons, against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
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
  conic_region_rule(p, static_cast<int>(polygon.size()), q, sign, line_rule(degree), line_rule(degree), 4, points);
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

// Random conics (ellipses, hyperbolas, parabolas, near-degenerate pairs of lines) over random convex polygons: the
// region's area and moments (of degree up to 4) equal the sums over the polygon cut in two by a random line, each
// half with its own frame, breakpoints and tangents. 2,000 draws at degree 10 (a P1 x P1 band's rule along) and 20:
// the largest difference 1.6e-11 at 10 (conics curving across the region, their tangents a region's width away;
// a band's conic is nearly straight across its thin region) and 1.8e-14 at 20, against a polygon's area of about 1.
TEST(ConicRegion, RandomConicsAddUpOverSplitPolygons) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst[2] = {0, 0};
  for (int draw = 0; draw < 2000; ++draw) {
    // a convex polygon: 3 to 7 points on a circle of radius 1 at sorted random angles
    const int m = 3 + draw % 5;
    std::vector<double> angle(m);
    for (double& a : angle) a = kPi * (1 + u(rng));
    std::sort(angle.begin(), angle.end());
    std::vector<std::array<double, 2>> polygon;
    for (double a : angle) polygon.push_back({{std::cos(a), std::sin(a)}});
    Quadratic2 q;
    q.c0 = 0.5 * u(rng);
    q.cu = u(rng);
    q.cv = u(rng);
    q.cuu = u(rng);
    q.cuv = u(rng);
    q.cvv = draw % 7 == 0 ? 1e-9 * u(rng) : u(rng);  // nearly parabolic in v, now and then
    if (draw % 11 == 0) {  // nearly two crossing lines: q = (u - v)(u + v) + eps
      q = Quadratic2();
      q.c0 = 1e-10 * u(rng);
      q.cuu = 1;
      q.cvv = -1;
    }
    // the cut: a line through a random interior point (the polygon's vertex mean, moved)
    double cx = 0, cy = 0;
    for (const auto& p : polygon) {
      cx += p[0] / m;
      cy += p[1] / m;
    }
    const double nx = u(rng), ny = u(rng), c = nx * cx + ny * cy;
    std::vector<std::array<double, 2>> halves[2];
    for (int i = 0; i < m; ++i) {
      const auto &p = polygon[i], &r = polygon[(i + 1) % m];
      const double sp = nx * p[0] + ny * p[1] - c, sr = nx * r[0] + ny * r[1] - c;
      halves[sp >= 0 ? 0 : 1].push_back(p);
      if ((sp >= 0) != (sr >= 0)) {
        const double t = sp / (sp - sr);
        const std::array<double, 2> x{{p[0] + t * (r[0] - p[0]), p[1] + t * (r[1] - p[1])}};
        halves[0].push_back(x);
        halves[1].push_back(x);
      }
    }
    for (int degree : {10, 20}) {
      for (int sign : {1, -1}) {
        const Moments whole = integrate(polygon, q, sign, degree);
        Moments sum;
        for (const auto& half : halves) {
          if (half.size() < 3) continue;
          const Moments h = integrate(half, q, sign, degree);
          sum.area += h.area;
          sum.x += h.x;
          sum.xx += h.xx;
          sum.xy4 += h.xy4;
        }
        const double e = std::max({std::fabs(whole.area - sum.area), std::fabs(whole.x - sum.x),
                                   std::fabs(whole.xx - sum.xx), std::fabs(whole.xy4 - sum.xy4)});
        worst[degree == 10 ? 0 : 1] = std::max(worst[degree == 10 ? 0 : 1], e);
      }
    }
  }
  std::printf("the largest difference: %.3g at degree 10, %.3g at 20\n", worst[0], worst[1]);
  EXPECT_LT(worst[0], 1e-10);
  EXPECT_LT(worst[1], 1e-13);
}

namespace {

// The area of {q > 0} for q = -h - kappa (|p - c|^2 - r^2) near the edge from a to b of a triangle, h the distance
// from the edge's line towards the triangle, c the edge's midpoint, 2 r its length: the conic passes through a and
// b, and in coordinates (s along the edge from c, h) the region is 0 < h < h*(s) = (sqrt(1 + 4 kappa^2 (r^2 - s^2))
// - 1) / (2 kappa) for |s| < r, a sliver of height about kappa r^2 (inside the triangle for the kappas below).
// Integrated in s by composite Gauss-Legendre on 64 panels: independent of the region's rule.
double sliver_area(double r, double kappa) {
  const LineRule& g = line_rule(20);
  double area = 0;
  const int panels = 64;
  for (int p = 0; p < panels; ++p) {
    const double s0 = -r + 2 * r * p / panels, ds = 2 * r / panels;
    for (size_t k = 0; k < g.nodes.size(); ++k) {
      const double s = s0 + g.nodes[k] * ds;
      const double w = 4 * kappa * kappa * (r * r - s * s);
      area += g.weights[k] * ds * (w / (std::sqrt(1 + w) + 1)) / (2 * kappa);  // (sqrt(1 + w) - 1) / (2 kappa)
    }
  }
  return area;
}

}  // namespace

// A conic through two vertices of the polygon, the region a sliver along the edge between them. At the vertices q
// rounds to either side of 0, and where both land below it the roots on the edge land just outside it: the region
// was taken for empty (one of a 3D band's regions on a solid face, on the fluid plane y = 0 of a mesh turned about
// y: the case below, from the plugin, whose sliver's area a 4000^2 count puts at 4.1944e-5, and a solid tetrahedron
// 9e-9 off at subdivide 2). Random triangles: the area against sliver_area's.
TEST(ConicRegion, ConicThroughTwoVerticesWithinRoundOff) {
  {
    Quadratic2 q;
    q.c0 = 0.011249999999999904;
    q.cu = -0.0037500000000000445;
    q.cv = -0.2887499999999999;
    q.cuu = -0.0075000000000000058;
    q.cuv = 0.0075000000000000058;
    const Moments m = integrate({{{0.25, 0.034313725490195734}}, {{0.25, 0.25}}, {{0.038461538461538158, 0.038461538461538158}}},
                                q, 1, 10);
    EXPECT_NEAR(m.area / 4.1944e-5, 1, 1e-3);
  }
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  int empty_before = 0;
  double worst = 0;
  for (int draw = 0; draw < 500; ++draw) {
    const std::array<double, 2> a{{u(rng), u(rng)}}, b{{u(rng), u(rng)}};
    const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
    if (len < 0.2) continue;
    const double nx = -ey / len, ny = ex / len;  // the triangle's side of the edge
    const std::array<double, 2> c{{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}};
    const std::array<double, 2> apex{{c[0] + nx * len, c[1] + ny * len}};
    const double r = 0.5 * len, kappa = 0.05 * (1.5 + u(rng)) / len;
    // q = -h - kappa (|p - c|^2 - r^2), h = n . (p - c)
    Quadratic2 q;
    q.cuu = -kappa;
    q.cvv = -kappa;
    q.cu = -nx + 2 * kappa * c[0];
    q.cv = -ny + 2 * kappa * c[1];
    q.c0 = nx * c[0] + ny * c[1] - kappa * (c[0] * c[0] + c[1] * c[1] - r * r);
    empty_before += q.at(a[0], a[1]) <= 0 && q.at(b[0], b[1]) <= 0;
    const double exact = sliver_area(r, kappa);
    for (int degree : {10, 20}) {
      const double area = integrate({a, b, apex}, q, 1, degree).area;
      worst = std::max(worst, std::fabs(area / exact - 1));
    }
  }
  std::printf("draws with q <= 0 at both vertices: %d; the largest relative difference %.3g\n", empty_before, worst);
  EXPECT_GT(empty_before, 0);  // the case the test is for
  EXPECT_LT(worst, 1e-10);
}
