// Newton's pull-back of many points at once (newton_pull_back_points) against the point-by-point iteration
// (newton_pull_back): the same answers and jacobians bit for bit, whether a point converges at the first
// iteration, at the second, after more (redone point by point) or meets a fold; and the answers are the
// reference points the test mapped forward.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "errors.hpp"
#include "map/pull_back.hpp"
#include "map/element_map.hpp"
#include "map/mapped_element.hpp"

using namespace dlmfsi;

namespace {

// On the solid triangle (0.2, 0.1), (1.1, 0.3), (0.4, 0.9): X(s) = R (s + w g(s)) + t with R a rotation by
// 0.4 and g(s) = (s1^2 s2 - s1^3, s1 s2^2), a cubic (degree 3: fitted), or the same without a known degree
// (evaluated by the map itself). w sets how far X is from affine; up to w = 0.2 det dX/ds > 0 on the
// triangle, and at s = (2, 0) det dX/ds = 1 - 12 w.
class CubicMap : public SolidMap {
 public:
  CubicMap(double w, bool fitted) : w_(w), fitted_(fitted) {}
  int degree() const override { return fitted_ ? 3 : -1; }
  MapValue evaluate(int, Point xi) const override {
    const Point s = from_reference(corners, xi);
    const Point z{s.x + w_ * (s.x * s.x * s.y - s.x * s.x * s.x), s.y + w_ * s.x * s.y * s.y};
    const double dz[2][2] = {{1 + w_ * (2 * s.x * s.y - 3 * s.x * s.x), w_ * s.x * s.x},
                             {w_ * s.y * s.y, 1 + w_ * 2 * s.x * s.y}};
    const double r[2][2] = {{c_, -s_}, {s_, c_}};
    MapValue v;
    v.x = {r[0][0] * z.x + r[0][1] * z.y + 0.3, r[1][0] * z.x + r[1][1] * z.y - 0.1};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) v.jac[a][b] = r[a][0] * dz[0][b] + r[a][1] * dz[1][b];
    return v;
  }
  static constexpr Point corners[3] = {{0.2, 0.1}, {1.1, 0.3}, {0.4, 0.9}};

 private:
  double w_;
  bool fitted_;
  double c_ = std::cos(0.4), s_ = std::sin(0.4);
};

Mesh one_triangle() {
  Mesh m;
  m.vertices.assign(CubicMap::corners, CubicMap::corners + 3);
  m.triangles = {{0, 1, 2}};
  m.build_adjacency();
  return m;
}

// Reference points inside the triangle, their images, and starting points: the answer itself (every
// fourth point), the answer moved by 1e-5 (every fourth), or the affine pull-back of the corners' images.
struct Points {
  std::vector<Point> xi, y, start;
};

Points points(const TriangleMap& map, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Point c0 = map.corner_image(0), c1 = map.corner_image(1), c2 = map.corner_image(2);
  const Point e1 = c1 - c0, e2 = c2 - c0;
  const double det = cross(e1, e2);
  Points p;
  for (int q = 0; q < n; ++q) {
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Point xi{a, b};
    const Point y = map.evaluate(xi).x;
    const Point d = y - c0;
    const Point affine{(d.x * e2.y - d.y * e2.x) / det, (e1.x * d.y - e1.y * d.x) / det};
    p.xi.push_back(xi);
    p.y.push_back(y);
    p.start.push_back(q % 4 == 0 ? xi : (q % 4 == 1 ? xi + Point{1e-5, -1e-5} : affine));
  }
  return p;
}

void expect_same_as_point_by_point(double w, bool fitted, double tolerance) {
  const Mesh mesh = one_triangle();
  const CubicMap cubic(w, fitted);
  TriangleMap map;
  map.fit(mesh, cubic, 0);
  ASSERT_EQ(map.fitted(), fitted);
  const int n = 203;
  const Points p = points(map, n, 7);
  const double round_off = 1e-15;
  std::vector<Point> xi = p.start;
  std::vector<std::array<double, 4>> jacobian(n);
  std::vector<double> scratch;
  newton_pull_back_points(map, round_off, n, p.y.data(), xi.data(), jacobian.data(), scratch);
  for (int q = 0; q < n; ++q) {
    SCOPED_TRACE("point " + std::to_string(q));
    MapValue value;
    const Point one = newton_pull_back(map, round_off, p.y[q], p.start[q], value);
    EXPECT_EQ(xi[q].x, one.x);
    EXPECT_EQ(xi[q].y, one.y);
    EXPECT_EQ(jacobian[q][0], value.jac[0][0]);
    EXPECT_EQ(jacobian[q][1], value.jac[0][1]);
    EXPECT_EQ(jacobian[q][2], value.jac[1][0]);
    EXPECT_EQ(jacobian[q][3], value.jac[1][1]);
    // the reference point mapped forward, and the map's own jacobian there
    EXPECT_NEAR(xi[q].x, p.xi[q].x, tolerance);
    EXPECT_NEAR(xi[q].y, p.xi[q].y, tolerance);
    const MapValue exact = cubic.evaluate(0, p.xi[q]);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) EXPECT_NEAR(jacobian[q][2 * a + b], exact.jac[a][b], 1e3 * tolerance);
  }
}

}  // namespace

// w = 0.005: most points converge at the second iteration; w = 0.2: many need more (redone point by point).
TEST(PullBackPoints, MatchPointByPointNewtonOnAMildCubic) { expect_same_as_point_by_point(0.005, true, 1e-14); }
TEST(PullBackPoints, MatchPointByPointNewtonOnAStrongCubic) { expect_same_as_point_by_point(0.2, true, 1e-13); }
TEST(PullBackPoints, MatchPointByPointNewtonOnAMapOfUnknownDegree) {
  expect_same_as_point_by_point(0.2, false, 1e-13);
}

// A start where the map folds (det dX/dxi < 0 outside the triangle): the same error as point by point.
TEST(PullBackPoints, AStartWhereTheMapFoldsThrowsTheSameError) {
  const Mesh mesh = one_triangle();
  const CubicMap cubic(0.2, true);
  TriangleMap map;
  map.fit(mesh, cubic, 0);
  // the reference point of s = (2, 0): s - s0 = (1.8, -0.1) in the edges (0.9, 0.2), (0.2, 0.8) (cross 0.68)
  const Point fold{(1.8 * 0.8 + 0.1 * 0.2) / 0.68, (-0.9 * 0.1 - 0.2 * 1.8) / 0.68};
  ASSERT_NEAR(from_reference(CubicMap::corners, fold).x, 2, 1e-12);
  Point x, d1, d2;
  map.polynomial(fold, x, d1, d2);
  ASSERT_LT(d1.x * d2.y - d2.x * d1.y, 0);
  std::vector<Point> y = {map.evaluate({0.3, 0.3}).x, map.evaluate({0.2, 0.5}).x};
  std::vector<Point> xi = {{0.3, 0.3}, fold};
  std::vector<std::array<double, 4>> jacobian(2);
  std::vector<double> scratch;
  std::string batch, one;
  try {
    newton_pull_back_points(map, 1e-15, 2, y.data(), xi.data(), jacobian.data(), scratch);
  } catch (const Error& e) {
    batch = e.what();
  }
  try {
    MapValue value;
    newton_pull_back(map, 1e-15, y[1], fold, value);
  } catch (const Error& e) {
    one = e.what();
  }
  EXPECT_NE(one.find("the map folds solid triangle 0"), std::string::npos) << one;
  EXPECT_EQ(batch, one);
}

namespace {

// A solid triangle of legs h at corner c: s0 = c, s1 = c + (h, 0), s2 = c + (0, h), under
// X(xi) = c + h (xi1 + 0.3 xi2 + w (xi1^2 xi2 - xi1^3), xi2 + w xi1 xi2^2), given by its monomial coefficients
// (exact: c and multiples of h). The displacement D(xi) = X(xi) - c is evaluated in long double as the
// reference.
class SmallCubic : public SolidMap {
 public:
  SmallCubic(Point c, double h, double w) : c_(c), h_(h), w_(w) {}
  int degree() const override { return 3; }
  bool coefficients(int, double* cx, double* cy) const override {
    const double x[10] = {c_.x, h_, 0.3 * h_, 0, 0, 0, -w_ * h_, w_ * h_, 0, 0};
    const double y[10] = {c_.y, 0, h_, 0, 0, 0, 0, 0, w_ * h_, 0};
    std::copy(x, x + 10, cx);
    std::copy(y, y + 10, cy);
    return true;
  }
  MapValue evaluate(int, Point xi) const override {
    const long double d[2] = {displacement(xi, 0), displacement(xi, 1)};
    MapValue v;
    v.x = {static_cast<double>(c_.x + d[0]), static_cast<double>(c_.y + d[1])};
    // dX/ds = dX/dxi / h (ds/dxi = h I)
    v.jac[0][0] = 1 + w_ * (2 * xi.x * xi.y - 3 * xi.x * xi.x);
    v.jac[0][1] = 0.3 + w_ * xi.x * xi.x;
    v.jac[1][0] = w_ * xi.y * xi.y;
    v.jac[1][1] = 1 + 2 * w_ * xi.x * xi.y;
    return v;
  }
  // D_a(xi) in long double.
  long double displacement(Point xi, int a) const {
    const long double s = xi.x, t = xi.y, h = h_, w = w_;
    return a == 0 ? h * (s + 0.3L * t + w * (s * s * t - s * s * s)) : h * (t + w * s * t * t);
  }
  Mesh mesh() const {
    Mesh m;
    m.vertices = {c_, {c_.x + h_, c_.y}, {c_.x, c_.y + h_}};
    m.triangles = {{0, 1, 2}};
    m.build_adjacency();
    return m;
  }

 private:
  Point c_;
  double h_, w_;
};

// The largest |y - X(xi)| / h over points y of the image, with xi pulled back from y (point by point and all
// at once): the residual is formed exactly ((y - c) is exact for y near c) against D in long double.
double worst_relative_residual(Point c, double h) {
  const SmallCubic cubic(c, h, 0.05);
  const Mesh mesh = cubic.mesh();
  MappedTriangle mt;
  mt.prepare(mesh, cubic, 0);
  EXPECT_FALSE(mt.affine);
  std::vector<Point> y, xi;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; i + j <= 8; ++j) {
      const Point at{i / 8.0, j / 8.0};
      y.push_back({static_cast<double>(c.x + cubic.displacement(at, 0)), static_cast<double>(c.y + cubic.displacement(at, 1))});
      xi.push_back(mt.affine_reference(y.back()));
    }
  std::vector<std::array<double, 4>> jacobian(y.size());
  std::vector<double> scratch;
  std::vector<Point> batch = xi;
  mt.pull_back_points(static_cast<int>(y.size()), y.data(), batch.data(), jacobian.data(), scratch);
  double worst = 0;
  for (size_t q = 0; q < y.size(); ++q) {
    MapValue value;
    for (const Point answer : {mt.pull_back(y[q], value), batch[q]})
      for (int a = 0; a < 2; ++a) {
        const long double y_c = a == 0 ? static_cast<long double>(y[q].x - c.x) : static_cast<long double>(y[q].y - c.y);
        worst = std::max(worst, static_cast<double>(std::fabs(y_c - cubic.displacement(answer, a)) / h));
      }
  }
  return worst;
}

}  // namespace

// A triangle of legs 1e-7 keeps, far from the origin, the accuracy it has at the origin: the residual of
// the pull-back is formed relative to the image (y - X(0)) - (X(xi) - X(0)), not in absolute coordinates,
// where y at distance R is known only to eps R, eps R / h = 1e-6 of the triangle at R = 1e3.
TEST(PullBack, ASmallTriangleFarFromTheOriginPullsBackToRoundOff) {
  const double h = 1e-7;
  for (const Point c : {Point{0, 0}, Point{0.5, 0.5}, Point{1e3, 1e3}, Point{-1e3, 2e3}}) {
    SCOPED_TRACE("c = (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ")");
    EXPECT_LT(worst_relative_residual(c, h), 1e-14);
  }
}
