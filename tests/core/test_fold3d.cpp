// The fold certification of curved 3D maps (fold3d.hpp) against maps whose jacobian determinant is known in
// closed form: a P2 map that folds inside a tetrahedron while its determinant is positive at the corners and
// at the points the assembly samples is an error; P2 maps close to folding but valid give 1'B1 = the solid's
// volume and int u(X(s)) ds against the polynomial integrated exactly; affine maps are never certified.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "coupling/coupling3d.hpp"
#include "errors.hpp"
#include "map/element_map3d.hpp"
#include "map/field_map3d.hpp"
#include "map/fold3d.hpp"
#include "map/pull_back3d.hpp"
#include "fe/matrix_inverse.hpp"
#include "fe/rules.hpp"
#include "support3d.hpp"

using namespace dlmfsi;
using namespace dlmfsi::test3d;

namespace {

// X(s) and dX/ds from a formula in the solid's coordinates, a polynomial of the given degree.
using Formula = std::function<void(Point3 s, Point3& x, double jac[3][3])>;
class FormulaMap3 : public SolidMap3 {
 public:
  FormulaMap3(const Mesh3& solid, Formula f, int degree) : solid_(solid), f_(std::move(f)), degree_(degree) {}
  MapValue3 evaluate(int k, Point3 xi) const override {
    Point3 p[4];
    solid_.corners(k, p);
    MapValue3 v;
    f_(from_reference(p, xi), v.x, v.jac);
    return v;
  }
  int degree() const override { return degree_; }

 private:
  const Mesh3& solid_;
  Formula f_;
  int degree_;
};

// det = u^2 + v^2 - gamma v, u = 1 + a (y - y0), v = a (x - x0): negative exactly in the cylinder about the
// axis x = x0 + gamma / (2a), y = y0 - 1 / a of radius |gamma / (2a)|, parallel to z.
//   X = (x + a (x - x0)(y - y0), y + gamma x - a/2 (x - x0)^2 + a/2 (y - y0)^2, z)
struct Cylinder {
  double a, x0, y0, gamma;
  void operator()(Point3 s, Point3& x, double j[3][3]) const {
    const double dx = s.x - x0, dy = s.y - y0;
    x = {s.x + a * dx * dy, s.y + gamma * s.x - a / 2 * dx * dx + a / 2 * dy * dy, s.z};
    const double jac[3][3] = {{1 + a * dy, a * dx, 0}, {gamma - a * dx, 1 + a * dy, 0}, {0, 0, 1}};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) j[r][c] = jac[r][c];
  }
  double det(Point3 s) const {
    const double u = 1 + a * (s.y - y0), v = a * (s.x - x0);
    return u * u + v * v - gamma * v;
  }
};

Mesh3 reference_tetrahedron() {
  Mesh3 m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tetrahedra = {{0, 1, 2, 3}};
  m.build_adjacency();
  return m;
}

CsrMatrix couple(const Mesh3& fluid, const Basis3& fluid_space, const Mesh3& solid, const Basis3& multiplier,
                 const SolidMap3& map, double c1, double c2, CouplingReport* report = nullptr) {
  CouplingOptions opt;
  opt.c1 = c1;
  opt.c2 = c2;
  const FluidSide3 fs(fluid, fluid_space, {0});
  const SolidSide3 ss(solid, multiplier, {0});
  return assemble_coupling(fs, ss, map, opt, report);
}

template <class Space>
std::vector<double> interpolate(const Space& space, const std::function<double(Point3)>& f) {
  std::vector<double> v(space.dof_count());
  for (int i = 0; i < space.dof_count(); ++i) v[i] = f(space.node(i));
  return v;
}

}  // namespace

TEST(Fold3d, FoldInsideATetrahedronIsAnError) {
  const Mesh3 solid = reference_tetrahedron();
  const Mesh3 fluid = box_mesh(4, 4, 4, {-4, -4, -4}, {8, 8, 8});
  // folds: cylinders about (0.1 - gamma / 8, 0.65) of radius gamma / 8, inside the tetrahedron for z < 0.2
  for (double gamma : {0.3, 0.05, 0.01, 0.002}) {
    const Cylinder c{-4, 0.1, 0.4, gamma};
    ASSERT_LT(c.det({0.1 - gamma / 8, 0.65, 0.1}), 0);
    // positive at the corners and at every point of the degree-8 lattice, which holds the corners of the
    // 8^2 sub-tetrahedra of a curved map's image and the lattice of the certification's first test
    for (int p = 0; p < monomial_count3(8); ++p) ASSERT_GT(c.det(lattice_point3(8, p)), 0) << p;
    const FormulaMap3 map(solid, c, 2);
    const std::string e = coupling_error(fluid, solid, map);
    EXPECT_NE(e.find("the map folds solid tetrahedron 0 (its jacobian determinant is not positive at reference point"),
              std::string::npos)
        << "gamma " << gamma << ": " << e;
  }
  // the same map with the fold moved off the tetrahedron (axis at x = -0.3375, 0.3 beyond the face x = 0)
  // is certified and assembled
  const Cylinder off{-4, -0.3, 0.4, 0.3};
  const FormulaMap3 valid(solid, off, 2);
  CouplingReport report;
  EXPECT_EQ(coupling_error(fluid, solid, valid, false, &report), "");
  EXPECT_EQ(report.curved, 1);
}

namespace {

// The P2 interpolant on the reference tetrahedron of the identity with the midpoint of edge (0, 1) slid by t
// along it: X = s + 4 t l0 l1 (v1 - v0) (l the barycentric coordinates), the corners and faces fixed, so
// the image is the tetrahedron itself; det dX/ds = 1 + 4t (l0 - l1) >= 1 - 4t (at vertex 1), a fold at t = 1/4.
Point3 slid(Point3 s, double t) {
  const double l0 = 1 - s.x - s.y - s.z, l1 = s.x;
  return {s.x + 4 * t * l0 * l1, s.y, s.z};
}

}  // namespace

TEST(Fold3d, P2MapsCloseToFoldingAreAccurate) {
  const Mesh3 solid = reference_tetrahedron();
  const Mesh3 fluid = box_mesh(3, 3, 3, {-0.5, -0.5, -0.5}, {2, 2, 2});
  const P2Tet map_space(solid), fluid_p2(fluid);
  const P1Tet multiplier(solid), fluid_p1(fluid);
  // u = y1^2 + y2 y3 + y3, exact in P2; int_T u(X(s)) ds by a degree-8 rule on T (u o X has degree 4)
  auto u = [](Point3 y) { return y.x * y.x + y.y * y.z + y.z; };
  const std::vector<double> u_dofs = interpolate(fluid_p2, u);
  auto map_for = [&](double t, std::vector<double> coef[3]) {
    for (int a = 0; a < 3; ++a) coef[a].resize(map_space.dof_count());
    for (int i = 0; i < map_space.dof_count(); ++i) {
      const Point3 x = slid(map_space.node(i), t);
      coef[0][i] = x.x;
      coef[1][i] = x.y;
      coef[2][i] = x.z;
    }
  };
  const Basis3* spaces[3] = {&map_space, &map_space, &map_space};
  const int comp[3] = {0, 0, 0};
  for (double t : {0.1, 0.2}) {
    std::vector<double> coef[3];
    map_for(t, coef);
    const double* c[3] = {coef[0].data(), coef[1].data(), coef[2].data()};
    const FieldMap3 map(solid, spaces, c, comp);
    double exact = 0;
    for (const RulePoint3& q : tetrahedron_rule(8)) exact += q.weight / 6 * u(slid(q.xi, t));
    CouplingReport report;
    const CsrMatrix volume = couple(fluid, fluid_p1, solid, multiplier, map, 0, 1, &report);
    double sum = 0;
    for (double v : volume.value) sum += v;
    EXPECT_NEAR(sum, 1.0 / 6, 1e-12 / 6) << "t " << t << ": " << report.summary();
    EXPECT_EQ(report.split, 1) << report.summary();
    const CsrMatrix b = couple(fluid, fluid_p2, solid, multiplier, map, 0, 1);
    EXPECT_NEAR(bilinear(b, std::vector<double>(4, 1.0), u_dofs), exact, 1e-12 * exact) << "t " << t;
  }
  // within 4e-4 of the fold: more than 20000 parts, a near fold; beyond it: det < 0 at corner 1, a fold
  for (double t : {0.2499, 0.26}) {
    std::vector<double> coef[3];
    map_for(t, coef);
    const double* c[3] = {coef[0].data(), coef[1].data(), coef[2].data()};
    const FieldMap3 map(solid, spaces, c, comp);
    const std::string e = coupling_error(fluid, solid, map);
    EXPECT_NE(e.find(t < 0.25 ? "the map nearly folds solid tetrahedron 0"
                              : "the map folds solid tetrahedron 0 (its jacobian "
                                "determinant is not positive at reference point (1, 0, 0))"),
              std::string::npos)
        << "t " << t << ": " << e;
  }
}

TEST(Fold3d, AffineP2MapsGiveTheP1MatricesBitForBit) {
  // A rotated, sheared affine map as a P1 and as a P2 field: the P2 one is recognised as affine, so its
  // matrices are the P1 one's bit for bit (the corners and the constant jacobian come from the same dofs).
  const Mesh3 solid = box_mesh(2, 2, 2, {0.3, 0.3, 0.3}, {0.4, 0.4, 0.4}, 0.2, 5);
  const Mesh3 fluid = box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1}, 0.2, 6);
  double r[3][3];
  rotation({1, 2, 3}, 0.7, r);
  r[0][1] += 0.3;  // a shear
  auto affine = [&](Point3 s) {
    const Point3 d = s - Point3{0.5, 0.5, 0.5};
    return Point3{0.5 + r[0][0] * d.x + r[0][1] * d.y + r[0][2] * d.z,
                  0.5 + r[1][0] * d.x + r[1][1] * d.y + r[1][2] * d.z,
                  0.5 + r[2][0] * d.x + r[2][1] * d.y + r[2][2] * d.z};
  };
  const P1Tet p1(solid), multiplier(solid), fluid_p1(fluid);
  const P2Tet p2(solid), fluid_p2(fluid);
  auto field = [&](const auto& space, std::vector<double> coef[3]) {
    for (int a = 0; a < 3; ++a) coef[a].resize(space.dof_count());
    for (int i = 0; i < space.dof_count(); ++i) {
      const Point3 x = affine(space.node(i));
      coef[0][i] = x.x;
      coef[1][i] = x.y;
      coef[2][i] = x.z;
    }
  };
  std::vector<double> c1[3], c2[3];
  field(p1, c1);
  field(p2, c2);
  const int comp[3] = {0, 0, 0};
  const Basis3* s1[3] = {&p1, &p1, &p1};
  const Basis3* s2[3] = {&p2, &p2, &p2};
  const double* v1[3] = {c1[0].data(), c1[1].data(), c1[2].data()};
  const double* v2[3] = {c2[0].data(), c2[1].data(), c2[2].data()};
  const FieldMap3 map1(solid, s1, v1, comp), map2(solid, s2, v2, comp);
  for (const Basis3* f : {static_cast<const Basis3*>(&fluid_p1), static_cast<const Basis3*>(&fluid_p2)}) {
    CouplingReport report1, report2;
    const CsrMatrix b1 = couple(fluid, *f, solid, multiplier, map1, 0.5, 2, &report1);
    const CsrMatrix b2 = couple(fluid, *f, solid, multiplier, map2, 0.5, 2, &report2);
    EXPECT_EQ(report2.affine, solid.size()) << report2.summary();
    EXPECT_EQ(report2.split, 0);
    ASSERT_EQ(b1.value.size(), b2.value.size());
    EXPECT_EQ(b1.start, b2.start);
    EXPECT_EQ(b1.column, b2.column);
    for (size_t e = 0; e < b1.value.size(); ++e) ASSERT_EQ(b1.value[e], b2.value[e]) << e;
  }
}

TEST(Fold3d, BubbleMapsUpToTheFoldAreAccurate) {
  // X = s + 256 b l0 l1 l2 l3 e1 on the reference tetrahedron, a P1b-like map of degree 4: the bubble
  // vanishes on the faces, so the image is the tetrahedron itself; det dX/ds = 1 + 256 b d(l0 x y z)/dx
  // = 1 - 256 b y z (2x + y + z - 1), smallest at the centre of the face l0 = 0: 1 - 256 b / 27, a fold at
  // b = 27/256.
  const Mesh3 solid = reference_tetrahedron();
  const Mesh3 fluid = box_mesh(3, 3, 3, {-0.5, -0.5, -0.5}, {2, 2, 2});
  const P1Tet multiplier(solid), fluid_p1(fluid);
  const P2Tet fluid_p2(fluid);
  auto u = [](Point3 y) { return y.x * y.x + y.y * y.z + y.z; };
  const std::vector<double> u_dofs = interpolate(fluid_p2, u);
  const double fold = 27.0 / 256;
  for (double f : {0.2, 0.3, 0.5, 1.01}) {
    const double b = f * fold;
    auto x_of = [b](Point3 s) { return Point3{s.x + 256 * b * (1 - s.x - s.y - s.z) * s.x * s.y * s.z, s.y, s.z}; };
    const FormulaMap3 map(
        solid,
        [&](Point3 s, Point3& x, double j[3][3]) {
          x = x_of(s);
          const double l0 = 1 - s.x - s.y - s.z, c = 256 * b;
          const double row[3] = {1 + c * s.y * s.z * (l0 - s.x), c * s.x * s.z * (l0 - s.y),
                                 c * s.x * s.y * (l0 - s.z)};
          for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) j[r][col] = r == 0 ? row[col] : (r == col ? 1 : 0);
        },
        4);
    if (f > 1) {
      const std::string e = coupling_error(fluid, solid, map);
      EXPECT_NE(e.find("the map folds solid tetrahedron 0 (its jacobian determinant is not positive at reference "
                       "point (0.333, 0.333, 0.333))"),
                std::string::npos)
          << e;
      continue;
    }
    // u o X has degree 8: the degree-8 rule on the tetrahedron is exact
    double exact = 0;
    for (const RulePoint3& q : tetrahedron_rule(8)) exact += q.weight / 6 * u(x_of(q.xi));
    CouplingReport report;
    const CsrMatrix volume = couple(fluid, fluid_p1, solid, multiplier, map, 0, 1, &report);
    double sum = 0;
    for (double v : volume.value) sum += v;
    EXPECT_NEAR(sum, 1.0 / 6, 1e-12 / 6) << "b " << f << " of the fold: " << report.summary();
    const CsrMatrix bu = couple(fluid, fluid_p2, solid, multiplier, map, 0, 1);
    EXPECT_NEAR(bilinear(bu, std::vector<double>(4, 1.0), u_dofs), exact, 1e-12 * exact) << "b " << f;
  }
}

TEST(Fold3d, BernsteinCertificateAgainstDenseSampling) {
  // Random cubics c + sum of products of three affine functions: a "positive" verdict must hold at every
  // point of the degree-48 lattice, a "folds" one must name a point where the cubic is <= 0.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coef(-1, 1);
  int verdicts[3] = {0, 0, 0};
  for (int trial = 0; trial < 300; ++trial) {
    double a[3][4];
    for (auto& row : a)
      for (double& v : row) v = coef(rng);
    const double c = 0.3 * (trial % 5) * std::fabs(coef(rng)) + 0.05;
    auto p = [&](Point3 x) {
      double prod = 1;
      for (const auto& row : a) prod *= row[0] + row[1] * x.x + row[2] * x.y + row[3] * x.z;
      return c + prod;
    };
    Point3 where;
    int tested = 0;
    const JacobianSign s = jacobian_sign3(
        [&](Point3 x) {
          return DetSample{p(x), 1e-15};
        },
        3, 10, 4096, where, &tested);
    ++verdicts[static_cast<int>(s)];
    if (s == JacobianSign::Positive) {
      for (int q = 0; q < monomial_count3(48); ++q) ASSERT_GT(p(lattice_point3(48, q)), 0) << trial;
    } else if (s == JacobianSign::Folds) {
      EXPECT_LE(p(where), 0) << trial;
      EXPECT_GE(where.x, 0);
      EXPECT_GE(where.y, 0);
      EXPECT_GE(where.z, 0);
      EXPECT_LE(where.x + where.y + where.z, 1 + 1e-15);
    }
  }
  // both verdicts occur; and a cubic positive with a minimum of 1e-3 inside (not at a lattice point) is
  // certified only after refinement, one touching zero there is a near fold
  EXPECT_GT(verdicts[static_cast<int>(JacobianSign::Positive)], 30);
  EXPECT_GT(verdicts[static_cast<int>(JacobianSign::Folds)], 30);
  for (double m : {1e-3, 0.0}) {
    const Point3 o{0.21, 0.17, 0.23};
    auto p = [&](Point3 x) {
      const Point3 d = x - o;
      return DetSample{m + dot(d, d) * (1 + d.x), 1e-15};
    };
    Point3 where;
    int tested = 0;
    const JacobianSign s = jacobian_sign3(p, 3, 10, 4096, where, &tested);
    EXPECT_EQ(s, m > 0 ? JacobianSign::Positive : JacobianSign::NearlyFolds) << m;
    EXPECT_GT(tested, 8) << m;
  }
}

namespace {

// Fits formula (a polynomial of the given degree) on the tetrahedron of the given corners and calls
// check(tm, xi, x, j, x0) at 50 random reference points xi, with the formula's X (x) and dX/ds (j) there and
// its X at corner 0 (x0).
void at_random_points(const Formula& formula, int degree, const std::vector<Point3>& vertices, unsigned seed,
                      const std::function<void(const TetrahedronMap&, Point3, Point3, const double (&)[3][3],
                                               Point3)>& check) {
  Mesh3 solid;
  solid.vertices = vertices;
  solid.tetrahedra = {{0, 1, 2, 3}};
  solid.build_adjacency();
  const FormulaMap3 map(solid, formula, degree);
  TetrahedronMap tm;
  tm.fit(solid, map, 0);
  ASSERT_EQ(tm.fitted_degree(), degree);
  Point3 corner[4];
  solid.corners(0, corner);
  Point3 x0;
  double j[3][3];
  formula(corner[0], x0, j);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int n = 0; n < 50; ++n) {
    Point3 xi{u(rng), u(rng), u(rng)};
    if (xi.x + xi.y + xi.z > 1) xi = {xi.x / 3, xi.y / 3, xi.z / 3};
    Point3 x;
    formula(from_reference(corner, xi), x, j);
    check(tm, xi, x, j, x0);
  }
}

// X alone and the displacement alone (TetrahedronMap::position, displacement_position) at xi: the formula's
// values x and x - x0, and bit for bit those of the sums that form the derivatives too.
void expect_positions(const TetrahedronMap& tm, Point3 xi, Point3 x, Point3 x0) {
  const Point3 p = tm.position(xi), dp = tm.displacement_position(xi);
  EXPECT_NEAR(p.x, x.x, 1e-13);
  EXPECT_NEAR(p.y, x.y, 1e-13);
  EXPECT_NEAR(p.z, x.z, 1e-13);
  EXPECT_NEAR(dp.x, x.x - x0.x, 1e-13);
  EXPECT_NEAR(dp.y, x.y - x0.y, 1e-13);
  EXPECT_NEAR(dp.z, x.z - x0.z, 1e-13);
  Point3 v, dv[3], d, dd[3];
  tm.reference_derivatives(xi, v, dv);
  tm.displacement(xi, d, dd);
  EXPECT_TRUE(p.x == v.x && p.y == v.y && p.z == v.z);
  EXPECT_TRUE(dp.x == d.x && dp.y == d.y && dp.z == d.z);
}

}  // namespace

// TetrahedronMap's quadratic evaluation (written out for P23d maps) against a quadratic with all ten monomials
// in each component, on a tetrahedron away from the origin: X, dX/ds and the displacement X - X(corner 0) at
// random reference points, and X and the displacement alone, against the formula evaluated directly.
TEST(TetrahedronMap, AFullQuadraticAndItsJacobianMatchTheFormula) {
  const double q[3][10] = {{0.3, 1.1, -0.2, 0.4, 0.05, -0.07, 0.11, 0.02, -0.09, 0.06},
                           {-0.1, 0.2, 0.9, -0.3, -0.04, 0.08, 0.03, -0.12, 0.05, 0.07},
                           {0.2, -0.25, 0.15, 1.2, 0.09, 0.01, -0.06, 0.04, 0.1, -0.08}};
  // X_a(s) = q0 + q1 x + q2 y + q3 z + q4 x^2 + q5 x y + q6 y^2 + q7 x z + q8 y z + q9 z^2
  const Formula quadratic = [&q](Point3 s, Point3& x, double j[3][3]) {
    double v[3];
    for (int a = 0; a < 3; ++a) {
      const double* c = q[a];
      v[a] = c[0] + c[1] * s.x + c[2] * s.y + c[3] * s.z + c[4] * s.x * s.x + c[5] * s.x * s.y + c[6] * s.y * s.y +
             c[7] * s.x * s.z + c[8] * s.y * s.z + c[9] * s.z * s.z;
      j[a][0] = c[1] + 2 * c[4] * s.x + c[5] * s.y + c[7] * s.z;
      j[a][1] = c[2] + c[5] * s.x + 2 * c[6] * s.y + c[8] * s.z;
      j[a][2] = c[3] + c[7] * s.x + c[8] * s.y + 2 * c[9] * s.z;
    }
    x = {v[0], v[1], v[2]};
  };
  at_random_points(quadratic, 2, {{2.0, 1.0, 3.0}, {2.4, 1.1, 3.0}, {2.1, 1.5, 3.1}, {2.0, 1.2, 3.45}}, 7,
                   [](const TetrahedronMap& tm, Point3 xi, Point3 x, const double (&j)[3][3], Point3 x0) {
                     const MapValue3 v = tm.at(xi);
                     EXPECT_NEAR(v.x.x, x.x, 1e-13);
                     EXPECT_NEAR(v.x.y, x.y, 1e-13);
                     EXPECT_NEAR(v.x.z, x.z, 1e-13);
                     for (int a = 0; a < 3; ++a)
                       for (int b = 0; b < 3; ++b) EXPECT_NEAR(v.jac[a][b], j[a][b], 1e-12) << a << b;
                     Point3 d, dxi[3];
                     tm.displacement(xi, d, dxi);
                     EXPECT_NEAR(d.x, x.x - x0.x, 1e-13);
                     EXPECT_NEAR(d.y, x.y - x0.y, 1e-13);
                     EXPECT_NEAR(d.z, x.z - x0.z, 1e-13);
                     expect_positions(tm, xi, x, x0);
                   });
}

// X and the displacement alone for a cubic map (the general sums), against the formula.
TEST(TetrahedronMap, PositionOfACubicMatchesTheFormula) {
  const Formula cubic = [](Point3 s, Point3& x, double j[3][3]) {
    x = {s.x + 0.1 * s.x * s.x * s.x, s.y + 0.2 * s.y * s.y * s.z, s.z - 0.15 * s.x * s.y * s.z + 0.05 * s.z * s.z};
    const double jj[3][3] = {{1 + 0.3 * s.x * s.x, 0, 0},
                             {0, 1 + 0.4 * s.y * s.z, 0.2 * s.y * s.y},
                             {-0.15 * s.y * s.z, -0.15 * s.x * s.z, 1 - 0.15 * s.x * s.y + 0.1 * s.z}};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) j[a][b] = jj[a][b];
  };
  at_random_points(cubic, 3, {{0.5, -0.3, 0.2}, {1.1, -0.2, 0.25}, {0.6, 0.4, 0.1}, {0.55, -0.1, 0.9}}, 11,
                   [](const TetrahedronMap& tm, Point3 xi, Point3 x, const double (&)[3][3], Point3 x0) {
                     expect_positions(tm, xi, x, x0);
                   });
}

// A cubic map (not quadratic: the reference side's general branch, X evaluated along each band column) on a
// solid box of 48 tetrahedra over a fluid box: lambda^T B u for data polynomial over the image (u of degree 1
// and 2, lambda affine), mass and gradient terms, against the same integral over the solid tetrahedra by a rule
// exact for it (u o X of degree 6, lambda (u o X) of degree 7; the gradient term of degree 5: the rule of degree 8).
// With u of degree 1 both gradients are constant on their elements (the chain rule summed per piece from the
// points' jacobians), with degree 2 not.
TEST(TetrahedronMap, CubicMapCouplingOfPolynomialDataIsExact) {
  const Mesh3 solid = box_mesh(2, 2, 2, {-0.3, -0.25, -0.2}, {0.6, 0.5, 0.45});
  const Mesh3 fluid = box_mesh(4, 4, 4, {-0.8, -0.8, -0.8}, {1.6, 1.6, 1.6});
  auto x_of = [](Point3 s, double j[3][3]) {
    j[0][0] = 1 + 0.9 * s.x * s.x + 0.2 * s.y;
    j[0][1] = 0.2 * s.x;
    j[0][2] = 0;
    j[1][0] = 0.3 * s.z;
    j[1][1] = 1 - 0.6 * s.y * s.z;
    j[1][2] = 0.3 * s.x - 0.3 * s.y * s.y;
    j[2][0] = 0.4 * s.y * s.z;
    j[2][1] = 0.4 * s.x * s.z;
    j[2][2] = 1 + 0.4 * s.x * s.y + 0.6 * s.z * s.z;
    return Point3{s.x + 0.3 * s.x * s.x * s.x + 0.2 * s.x * s.y, s.y - 0.3 * s.y * s.y * s.z + 0.3 * s.x * s.z,
                  s.z + 0.4 * s.x * s.y * s.z + 0.2 * s.z * s.z * s.z};
  };
  const FormulaMap3 map(solid, [&](Point3 s, Point3& x, double j[3][3]) { x = x_of(s, j); }, 3);
  const P1Tet multiplier(solid), fluid_p1(fluid);
  const P2Tet fluid_p2(fluid);
  auto lambda = [](Point3 s) { return 1 + 0.5 * s.x - 0.3 * s.y + 0.2 * s.z; };
  const Point3 grad_lambda{0.5, -0.3, 0.2};
  const std::vector<double> lam = interpolate(multiplier, lambda);
  struct Data {
    const Basis3& space;
    std::function<double(Point3)> u;
    std::function<Point3(Point3)> grad_u;
    std::vector<double> dofs;
  };
  auto u1 = [](Point3 y) { return 0.3 + y.x - 2 * y.y + y.z; };
  auto u2 = [](Point3 y) { return y.x * y.x + y.y * y.z - y.z; };
  const Data data[2] = {{fluid_p1, u1, [](Point3) { return Point3{1, -2, 1}; }, interpolate(fluid_p1, u1)},
                        {fluid_p2, u2, [](Point3 y) { return Point3{2 * y.x, y.z, y.y - 1}; }, interpolate(fluid_p2, u2)}};
  for (const Data& d : data) {
    const std::vector<double>& u = d.dofs;
    for (double c1 : {0.0, 0.7}) {
      const double c2 = 1.3;
      double exact = 0;  // int_S c2 lambda u(X) + c1 grad lambda . (dX/ds^T grad u(X)) ds
      for (int k = 0; k < static_cast<int>(solid.tetrahedra.size()); ++k) {
        Point3 corner[4];
        solid.corners(k, corner);
        const double volume = dot(corner[1] - corner[0], cross(corner[2] - corner[0], corner[3] - corner[0])) / 6;
        for (const RulePoint3& q : tetrahedron_rule(8)) {
          const Point3 s = from_reference(corner, q.xi);
          double j[3][3];
          const Point3 y = x_of(s, j);
          const Point3 g = d.grad_u(y);
          const Point3 jt{j[0][0] * g.x + j[1][0] * g.y + j[2][0] * g.z, j[0][1] * g.x + j[1][1] * g.y + j[2][1] * g.z,
                          j[0][2] * g.x + j[1][2] * g.y + j[2][2] * g.z};
          exact += q.weight * volume * (c2 * lambda(s) * d.u(y) + c1 * dot(grad_lambda, jt));
        }
      }
      CouplingReport report;
      const CsrMatrix b = couple(fluid, d.space, solid, multiplier, map, c1, c2, &report);
      EXPECT_NEAR(bilinear(b, lam, u), exact, 1e-13 * std::fabs(exact))
          << "fluid degree " << (&d.space == &fluid_p1 ? 1 : 2) << ", c1 " << c1 << ": " << report.summary();
    }
  }
}

// A P1b map on a general tetrahedron, X(s) = A s + t + beta q(xi(s)), q = xi1 xi2 xi3 (1 - xi1 - xi2 - xi3): the fit
// is recognised as an affine map plus a bubble (bubble_form), whose parts give X back at random points against the
// formula, and the pull-back (the bubble's scalar predictor, then Newton) returns the reference point the test
// mapped forward, with X and dX/ds there. A map with one more term (1e-3 x^2) is not of that form and pulls back
// all the same (Newton alone).
TEST(TetrahedronMap, BubbleMapsPullBackThroughTheirBubbleForm) {
  const Point3 v[4] = {{0.5, -0.3, 0.2}, {1.1, -0.2, 0.25}, {0.6, 0.4, 0.1}, {0.55, -0.1, 0.9}};
  double e_inv[3][3];
  inverse_of_columns(v[1] - v[0], v[2] - v[0], v[3] - v[0], e_inv);
  const double a[3][3] = {{0.9, -0.3, 0.1}, {0.35, 0.95, -0.2}, {-0.1, 0.15, 1.05}};
  const Point3 beta{0.12, -0.2, 0.08}, shift{0.3, -0.1, 0.2};
  for (double extra : {0.0, 1e-3}) {
    const Formula formula = [&](Point3 s, Point3& x, double j[3][3]) {
      const Point3 d = s - v[0];
      double xi[3];
      for (int i = 0; i < 3; ++i) xi[i] = e_inv[i][0] * d.x + e_inv[i][1] * d.y + e_inv[i][2] * d.z;
      const double l0 = 1 - xi[0] - xi[1] - xi[2], q = xi[0] * xi[1] * xi[2] * l0;
      const double dq[3] = {xi[1] * xi[2] * (l0 - xi[0]), xi[0] * xi[2] * (l0 - xi[1]),
                            xi[0] * xi[1] * (l0 - xi[2])};
      const double b[3] = {beta.x, beta.y, beta.z}, t[3] = {shift.x, shift.y, shift.z}, ss[3] = {s.x, s.y, s.z};
      double out[3];
      for (int r = 0; r < 3; ++r) {
        out[r] = t[r] + a[r][0] * s.x + a[r][1] * s.y + a[r][2] * s.z + b[r] * q;
        if (r == 0) out[r] += extra * s.x * s.x;
        for (int c = 0; c < 3; ++c) {  // dq/ds_c = sum_i dq/dxi_i dxi_i/ds_c
          const double dqds = dq[0] * e_inv[0][c] + dq[1] * e_inv[1][c] + dq[2] * e_inv[2][c];
          j[r][c] = a[r][c] + b[r] * dqds + (r == 0 && c == 0 ? 2 * extra * ss[0] : 0);
        }
      }
      x = {out[0], out[1], out[2]};
    };
    Mesh3 solid;
    solid.vertices.assign(v, v + 4);
    solid.tetrahedra = {{0, 1, 2, 3}};
    solid.build_adjacency();
    const FormulaMap3 map(solid, formula, 4);
    MappedTet mt;
    mt.prepare(solid, map, 0);
    EXPECT_EQ(mt.bubble_form(), extra == 0);
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(0, 1);
    for (int n = 0; n < 200; ++n) {
      Point3 xi{u(rng), u(rng), u(rng)};
      if (xi.x + xi.y + xi.z > 1) xi = {xi.x / 3, xi.y / 3, xi.z / 3};
      Point3 y;
      double j[3][3];
      formula(from_reference(v, xi), y, j);
      if (extra == 0) {  // X(0) + D xi + beta q(xi), and D v = beta
        const double q = xi.x * xi.y * xi.z * (1 - xi.x - xi.y - xi.z);
        const Point3 parts = mt.origin() + (xi.x * mt.bubble_linear(0) + xi.y * mt.bubble_linear(1) +
                                            xi.z * mt.bubble_linear(2)) + q * mt.bubble_beta();
        EXPECT_NEAR(parts.x, y.x, 1e-14);
        EXPECT_NEAR(parts.y, y.y, 1e-14);
        EXPECT_NEAR(parts.z, y.z, 1e-14);
        const Point3 dir = mt.bubble_direction();
        const Point3 dv = dir.x * mt.bubble_linear(0) + dir.y * mt.bubble_linear(1) + dir.z * mt.bubble_linear(2);
        EXPECT_NEAR(dv.x, mt.bubble_beta().x, 1e-15);
        EXPECT_NEAR(dv.y, mt.bubble_beta().y, 1e-15);
        EXPECT_NEAR(dv.z, mt.bubble_beta().z, 1e-15);
      }
      MapValue3 value;
      const Point3 back = pull_back(mt, y, mt.affine_reference(y), value);
      EXPECT_NEAR(back.x, xi.x, 1e-13) << extra;
      EXPECT_NEAR(back.y, xi.y, 1e-13) << extra;
      EXPECT_NEAR(back.z, xi.z, 1e-13) << extra;
      EXPECT_NEAR(value.x.x, y.x, 1e-13);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(value.jac[r][c], j[r][c], 1e-12) << r << c;
    }
  }
}
