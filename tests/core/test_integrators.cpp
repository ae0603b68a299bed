// The pieces of the assembly on their own: the local block, the component pairs, the piece integrators
// (each against an integral computed here from barycentric coordinates) and the rule degree for maps that
// are not affine.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/clip.hpp"
#include "fe/component_pairs.hpp"
#include "coupling/coupling.hpp"
#include "map/field_map.hpp"
#include "integration/integrate_batch.hpp"
#include "integration/integrate_moments.hpp"
#include "integration/integrate_points.hpp"
#include "integration/integrator.hpp"
#include "integration/local_block.hpp"
#include "fe/rules.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// A block's multiplier rows: global dofs 10, 11, 12.
struct Rows {
  void dofs(int, int* g) const {
    for (int i = 0; i < 3; ++i) g[i] = 10 + i;
  }
};

bool same(const Triplet& t, int row, int col, double value) {
  return t.row == row && t.col == col && t.value == value;
}

}  // namespace

TEST(LocalBlock, ColumnsFollowTheFluidDofsAndScatterSkipsUnusedRowsAndZeros) {
  LocalBlock block(3, {0, 2}, 3, {0, 1, 2});
  block.start(Rows{}, 0);
  const int first[3] = {5, 7, 9};
  block.enter_fluid_element(first);
  block.column(0)[0] = 1;  // (row 10, dof 5)
  block.column(2)[2] = 2;  // (12, 9)
  block.column(1)[1] = 3;  // row 11 is not used: never scattered
  const int second[3] = {9, 4, 5};  // dofs 9 and 5 have columns already, 4 is new
  block.enter_fluid_element(second);
  block.column(0)[0] += 4;  // (10, 9)
  block.column(1)[2] = 5;   // (12, 4)
  block.column(2)[0] += 6;  // (10, 5): 1 + 6
  std::vector<Triplet> out;
  block.scatter(out);
  ASSERT_EQ(out.size(), 4u);  // row by row, columns in the order their dofs came: 5, 7, 9, 4
  EXPECT_TRUE(same(out[0], 10, 5, 7));
  EXPECT_TRUE(same(out[1], 10, 9, 4));
  EXPECT_TRUE(same(out[2], 12, 9, 2));
  EXPECT_TRUE(same(out[3], 12, 4, 5));
  // The next element starts empty: new columns are zero whatever the entries held before.
  block.start(Rows{}, 1);
  block.enter_fluid_element(first);
  out.clear();
  block.scatter(out);
  EXPECT_TRUE(out.empty());
}

// A solid element outside the fluid mesh has no piece: no column was ever entered (the block's entries
// not even allocated), and both scatters add nothing (under make sanitize, reading the empty entries was
// an error).
TEST(LocalBlock, ABlockWithNoPieceScattersNothing) {
  LocalBlock block(3, {0, 1, 2}, 3, {0, 1, 2});
  block.start(Rows{}, 0);
  std::vector<Triplet> out;
  block.scatter(out);
  EXPECT_TRUE(out.empty());
  CsrBuilder builder;
  builder.build(20, 4, {std::vector<Triplet>{{10, 1, 1.0}}});
  InPlaceSum* sum = builder.sum_on_last_pattern(20, 4);
  ASSERT_NE(sum, nullptr);
  std::vector<Triplet> misses, later;
  block.scatter(*sum, misses, later);
  EXPECT_TRUE(misses.empty());
  EXPECT_TRUE(later.empty());
}

TEST(LocalBlock, KeepsItsEntriesWhileColumnsGrow) {
  LocalBlock block(3, {0, 1, 2}, 3, {0, 1, 2});
  block.start(Rows{}, 0);
  for (int e = 0; e < 40; ++e) {
    const int dofs[3] = {3 * e, 3 * e + 1, 3 * e + 2};
    block.enter_fluid_element(dofs);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) block.column(j)[i] = 1000 * i + dofs[j] + 1;
  }
  std::vector<Triplet> out;
  block.scatter(out);
  ASSERT_EQ(out.size(), 360u);
  for (size_t t = 0; t < out.size(); ++t) {
    const int row = static_cast<int>(t / 120), col = static_cast<int>(t % 120);
    EXPECT_TRUE(same(out[t], 10 + row, col, 1000 * row + col + 1)) << t;
  }
}

TEST(ComponentPairs, RangesFunctionsAndTwins) {
  const Mesh mesh = test::grid_mesh(2, 2, 0, 0, 1, 1);
  const test::VectorP1 fluid(mesh), multiplier(mesh), scaled(mesh, 2);
  const PolynomialBasis fluid_fit(fluid, mesh, 1, {0, 1}), multiplier_fit(multiplier, mesh, 1, {0, 1});
  const ComponentPairs pairs(fluid, fluid_fit, {0, 1}, multiplier, multiplier_fit, {0, 1});
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[1].fluid_first, 3);
  EXPECT_EQ(pairs[1].fluid_last, 6);
  EXPECT_EQ(pairs[1].solid_first, 3);
  // fitted functions dof * 2 + component, sorted: 0, 2, 4 (component 0), 7, 9, 11 (component 1)
  EXPECT_EQ(pairs[0].fluid_functions, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(pairs[1].fluid_functions, (std::vector<int>{3, 4, 5}));
  // component 1 repeats component 0 on both sides: pair 1 copies pair 0's sums
  EXPECT_EQ(pairs[0].source, -1);
  EXPECT_EQ(pairs[1].source, 0);
  EXPECT_EQ(pairs[0].copies, std::vector<int>{1});
  EXPECT_EQ(pairs.fluid_read(), (std::vector<char>{1, 1, 1, 1, 1, 1}));
  EXPECT_EQ(pairs.fluid_read_by_sources(), (std::vector<char>{1, 1, 1, 0, 0, 0}));
  EXPECT_EQ(pairs.used_fluid_dofs(), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  // a multiplier whose second component differs (twice the first): no twins
  const PolynomialBasis scaled_fit(scaled, mesh, 1, {0, 1});
  const ComponentPairs distinct(fluid, fluid_fit, {0, 1}, scaled, scaled_fit, {0, 1});
  EXPECT_EQ(distinct[1].source, -1);
  // one component only: the other's dofs are not used
  const ComponentPairs one(fluid, fluid_fit, {1}, multiplier, multiplier_fit, {0});
  EXPECT_EQ(one.used_fluid_dofs(), (std::vector<int>{3, 4, 5}));
  EXPECT_EQ(one.used_multiplier_dofs(), (std::vector<int>{0, 1, 2}));
}

namespace {

// Gradients of the barycentric coordinates of triangle p.
void barycentric_gradients(const Point p[3], double g[3][2]) {
  const double det = cross(p[1] - p[0], p[2] - p[0]);
  for (int i = 0; i < 3; ++i) {
    const Point a = p[(i + 1) % 3], b = p[(i + 2) % 3];
    g[i][0] = (a.y - b.y) / det;
    g[i][1] = (b.x - a.x) / det;
  }
}

// One fluid triangle, one solid triangle under X(s) = A s + b (a P1 map), and the piece X(T) ∩ F.
struct OnePiece {
  Mesh fluid, solid;
  double a[2][2] = {{0.9, -0.5}, {0.4, 1.2}};
  Point b{0.15, -0.1};
  std::vector<double> mx, my;
  test::P1 solid_p1{solid};

  OnePiece() {
    fluid.vertices = {{0, 0}, {1, 0.1}, {0.3, 0.9}};
    fluid.triangles = {{0, 1, 2}};
    fluid.build_adjacency();
    solid.vertices = {{0.1, 0.05}, {0.6, 0.2}, {0.05, 0.5}};
    solid.triangles = {{0, 1, 2}};
    solid.build_adjacency();
    for (Point s : solid.vertices) {
      mx.push_back(a[0][0] * s.x + a[0][1] * s.y + b.x);
      my.push_back(a[1][0] * s.x + a[1][1] * s.y + b.y);
    }
  }
  Point map(Point s) const { return {a[0][0] * s.x + a[0][1] * s.y + b.x, a[1][0] * s.x + a[1][1] * s.y + b.y}; }
  Point inverse(Point y) const {
    const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    const Point d = y - b;
    return {(a[1][1] * d.x - a[0][1] * d.y) / det, (a[0][0] * d.y - a[1][0] * d.x) / det};
  }
  Piece piece() const {
    Point image[3], f[3];
    for (int i = 0; i < 3; ++i) image[i] = map(solid.vertices[i]);
    fluid.corners(0, f);
    return clip(image, f);
  }
  // int_{X^-1(P)} c2 lambda_i phi_j + c1 grad_s lambda_i . (grad phi_j A) ds for the barycentric coordinates
  // lambda of T and phi of F (rows i, columns j), by a degree-2 rule on the piece's fan (exact).
  std::array<std::array<double, 3>, 3> reference(double c1, double c2) const {
    const Piece p = piece();
    Point f[3], t[3];
    fluid.corners(0, f);
    solid.corners(0, t);
    double gf[3][2], gt[3][2];
    barycentric_gradients(f, gf);
    barycentric_gradients(t, gt);
    const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    std::array<std::array<double, 3>, 3> out{};
    for (int k = 1; k + 1 < p.n; ++k) {
      const Point tri[3] = {p.v[0], p.v[k], p.v[k + 1]};
      const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
      for (const RulePoint& q : triangle_rule(2)) {
        const Point y = from_reference(tri, q.xi), lf = to_reference(f, y), lt = to_reference(t, inverse(y));
        const double phi[3] = {1 - lf.x - lf.y, lf.x, lf.y}, psi[3] = {1 - lt.x - lt.y, lt.x, lt.y};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const double g0 = gf[j][0] * a[0][0] + gf[j][1] * a[1][0], g1 = gf[j][0] * a[0][1] + gf[j][1] * a[1][1];
            out[i][j] += area * q.weight / det * (c2 * psi[i] * phi[j] + c1 * (gt[i][0] * g0 + gt[i][1] * g1));
          }
      }
    }
    return out;
  }
};

// The block of one piece under the given integrator kind (scalar P1 on both sides).
template <class Integrator>
std::array<std::array<double, 3>, 3> integrate_piece(const OnePiece& setup, double c1, double c2, bool chain,
                                                     CouplingReport& counts) {
  const test::P1 fluid_p1(setup.fluid);
  const PolynomialBasis fluid_fit(fluid_p1, setup.fluid, 1, {0}), solid_fit(setup.solid_p1, setup.solid, 1, {0});
  const ComponentPairs pairs(fluid_p1, fluid_fit, {0}, setup.solid_p1, solid_fit, {0});
  const Integrand integrand{fluid_p1, fluid_fit, setup.solid_p1, solid_fit, pairs, c1, c2, chain, 1, 1, 2};
  const FieldMap map(setup.solid, setup.solid_p1, setup.mx.data(), 0, setup.solid_p1, setup.my.data(), 0);
  MappedTriangle mt;
  mt.prepare(setup.solid, map, 0);
  EXPECT_TRUE(mt.affine);
  Integrator integrator(integrand, counts);
  LocalBlock block(3, {0, 1, 2}, 3, {0, 1, 2});
  block.start(setup.solid_p1, 0);
  const int fluid_dofs[3] = {0, 1, 2};
  block.enter_fluid_element(fluid_dofs);
  const Piece piece = setup.piece();
  const ClippedImage image{mt, 2, nullptr};
  integrator.start(image);
  // the area the exact method sums to find an image's part outside the fluid: piece.area(), bit for bit
  EXPECT_EQ(integrator.integrate(image, 0, piece, block), piece.area());
  std::array<std::array<double, 3>, 3> out{};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) out[i][j] = block.column(j)[i];
  return out;
}

template <class Integrator>
void expect_reference(double c1, double c2, long points_per_piece) {
  const OnePiece setup;
  ASSERT_GE(setup.piece().n, 4);  // a true cut: the piece is neither triangle
  CouplingReport counts;
  const auto got = integrate_piece<Integrator>(setup, c1, c2, true, counts);
  const auto want = setup.reference(c1, c2);
  double scale = 0;
  for (const auto& row : want)
    for (double v : row) scale = std::max(scale, std::fabs(v));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(got[i][j], want[i][j], 1e-14 * scale) << i << " " << j;
  if (points_per_piece > 0) {
    EXPECT_EQ(counts.points, points_per_piece);
  }
}

}  // namespace

TEST(PieceIntegrators, MomentsMatchTheBarycentricIntegral) {
  expect_reference<MomentIntegrator>(0, 1, 1);
  expect_reference<MomentIntegrator>(0.7, 1.3, 1);
}

TEST(PieceIntegrators, BatchMatchesTheBarycentricIntegral) {
  expect_reference<BatchIntegrator>(0, 1, -1);
  expect_reference<BatchIntegrator>(0.7, 1.3, -1);
}

TEST(PieceIntegrators, PointsMatchTheBarycentricIntegral) {
  expect_reference<PointIntegrator>(0, 1, -1);
  expect_reference<PointIntegrator>(0.7, 1.3, -1);
}

// The listings' product on [P1, P1] x [P1, P1]: entry (multiplier dof of component a, fluid dof of
// component c) = c1 (|P| / det A) A_ac grad_s lambda_i . grad phi_j, plus the mass term where a = c.
TEST(PieceIntegrators, PointsGiveTheListingsProduct) {
  const OnePiece setup;
  const test::VectorP1 fluid(setup.fluid), multiplier(setup.solid);
  const PolynomialBasis fluid_fit(fluid, setup.fluid, 1, {0, 1}), solid_fit(multiplier, setup.solid, 1, {0, 1});
  const ComponentPairs pairs(fluid, fluid_fit, {0, 1}, multiplier, solid_fit, {0, 1});
  const double c1 = 0.7, c2 = 1.3;
  const Integrand integrand{fluid, fluid_fit, multiplier, solid_fit, pairs, c1, c2, false, 1, 1, 2};
  const FieldMap map(setup.solid, setup.solid_p1, setup.mx.data(), 0, setup.solid_p1, setup.my.data(), 0);
  MappedTriangle mt;
  mt.prepare(setup.solid, map, 0);
  CouplingReport counts;
  PointIntegrator integrator(integrand, counts);
  LocalBlock block(6, {0, 1, 2, 3, 4, 5}, 6, {0, 1, 2, 3, 4, 5});
  block.start(multiplier, 0);
  const int fluid_dofs[6] = {0, 2, 4, 1, 3, 5};
  block.enter_fluid_element(fluid_dofs);
  const Piece piece = setup.piece();
  const ClippedImage image{mt, 2, nullptr};
  integrator.start(image);
  integrator.integrate(image, 0, piece, block);

  const auto mass = setup.reference(0, c2);
  Point f[3], t[3];
  setup.fluid.corners(0, f);
  setup.solid.corners(0, t);
  double gf[3][2], gt[3][2];
  barycentric_gradients(f, gf);
  barycentric_gradients(t, gt);
  const double det = setup.a[0][0] * setup.a[1][1] - setup.a[0][1] * setup.a[1][0];
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          double want = c1 * piece.area() / det * setup.a[a][c] * (gt[i][0] * gf[j][0] + gt[i][1] * gf[j][1]);
          if (a == c) want += mass[i][j];
          EXPECT_NEAR(block.column(3 * c + j)[3 * a + i], want, 1e-14) << a << c << i << j;
        }
}

// The comment's claim: the degree p + 2k with the smallest k >= 1 for which (d / 3)^(k+1) <= 1e-11.
TEST(RuleDegree, SmallestDegreeForTheErrorBound) {
  for (double d : {1e-12, 1e-6, 1e-3, 0.009, 0.05, 0.1, 0.2, 0.25}) {
    const int k = (nonlinear_rule_degree(3, d) - 3) / 2;
    EXPECT_EQ(nonlinear_rule_degree(3, d), 3 + 2 * k);
    EXPECT_LE(std::pow(d / 3, k + 1), 1e-11 * (1 + 1e-12)) << d;
    if (k > 1) {
      EXPECT_GT(std::pow(d / 3, k), 1e-11) << d;
    }
  }
  EXPECT_EQ(nonlinear_rule_degree(2, kLeafNonlinearity), 22);  // the split's target: p + 20
  EXPECT_EQ(nonlinear_rule_degree(2, 5.0), 22);                 // above the target: clamped to it
  EXPECT_EQ(nonlinear_rule_degree(55, 0.25), kMaxQforder);
}
