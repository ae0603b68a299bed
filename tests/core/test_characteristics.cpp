// The characteristics' right-hand side (plugin/core/transfer/characteristics.hpp) against independent references: a
// uniform velocity moves every point by dt * w (the walk across edges, along edges and through vertices);
// the boundary stops it where it meets it; with no velocity the vector is the P1 mass matrix (written here
// from |K| (1 + delta_ab) / 12) times the field, and with a uniform velocity the mass matrix times the
// shifted linear field on the rows whose support's feet stay in the domain.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "transfer/characteristics.hpp"
#include "errors.hpp"
#include "sides/sides.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// The unit square, 10 x 10 cells: vertex (i, j) at (i/10, j/10), [P1, P1] with global dof 2 v + c; turned
// by angle about the origin when given (the grid's lines then have slopes that round).
Mesh turned(Mesh mesh, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (Point& v : mesh.vertices) v = {c * v.x - s * v.y, s * v.x + c * v.y};
  return mesh;
}

double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }

struct Square {
  explicit Square(double angle = 0) : mesh(turned(test::grid_mesh(10, 10, 0, 0, 1, 1), angle)) {}
  Mesh mesh;
  test::VectorP1 space{mesh};
  FluidSide side{mesh, space, {0, 1}};
  // A [P1, P1] vector with components f0 and f1 at the vertices.
  template <class F0, class F1>
  std::vector<double> interpolate(F0 f0, F1 f1) const {
    std::vector<double> v(2 * mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      v[2 * i] = f0(mesh.vertices[i]);
      v[2 * i + 1] = f1(mesh.vertices[i]);
    }
    return v;
  }
  // The P1 mass matrix times g, component by component (the exact integrals of products of hat functions).
  std::vector<double> mass_times(const std::vector<double>& g) const {
    std::vector<double> b(g.size(), 0.0);
    for (int k = 0; k < mesh.size(); ++k) {
      Point p[3];
      mesh.corners(k, p);
      const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 2; ++c)
          for (int e = 0; e < 3; ++e)
            b[2 * mesh.triangles[k][a] + c] += area / 12 * (a == e ? 2 : 1) * g[2 * mesh.triangles[k][e] + c];
    }
    return b;
  }
  Point where(const Foot& f) const {
    Point p[3];
    side.mesh().corners(f.k, p);
    return from_reference(p, f.xi);
  }
};

CharacteristicsTerm uniform_term(const std::vector<double>& velocity, double dt) {
  CharacteristicsTerm term;
  term.velocity = velocity.data();
  term.field = velocity.data();
  term.dt = dt;
  return term;
}

}  // namespace

TEST(Characteristics, AUniformVelocityMovesEveryPointByDtTimesItAcrossEdges) {
  const Square s;
  const std::vector<double> w = s.interpolate([](Point) { return 0.13; }, [](Point) { return -0.07; });
  const Characteristics c(s.side, uniform_term(w, -2.0));  // back by (-0.26, 0.14): up to five cells
  CharacteristicsReport report;
  int traced = 0;
  for (int k = 0; k < s.side.mesh().size(); ++k) {
    Point p[3];
    s.side.mesh().corners(k, p);
    const Point x = from_reference(p, {0.2, 0.3});
    if (x.x < 0.3 || x.y > 0.8) continue;  // the foot would leave the square
    const Foot f = c.trace(k, {0.2, 0.3}, &report);
    const Point y = s.where(f);
    EXPECT_FALSE(f.at_boundary);
    EXPECT_NEAR(y.x, x.x - 0.26, 1e-14);
    EXPECT_NEAR(y.y, x.y + 0.14, 1e-14);
    ++traced;
  }
  EXPECT_GT(traced, 80);
  EXPECT_GT(report.crossings, 3 * traced);
  EXPECT_EQ(report.boundary_stops, 0);
}

TEST(Characteristics, TheBoundaryStopsTheWalkWhereItMeetsIt) {
  const Square s;
  const std::vector<double> w = s.interpolate([](Point) { return 1.0; }, [](Point) { return 0.5; });
  const Characteristics c(s.side, uniform_term(w, -1.0));
  for (int k = 0; k < s.side.mesh().size(); ++k) {
    Point p[3];
    s.side.mesh().corners(k, p);
    const Point x = from_reference(p, {0.25, 0.25});
    if (x.y < 0.6) continue;  // the line back meets x = 0 at y = x.y - x.x / 2 >= 0.1
    const Foot f = c.trace(k, {0.25, 0.25});
    const Point y = s.where(f);
    EXPECT_TRUE(f.at_boundary);
    EXPECT_NEAR(y.x, 0, 1e-15);
    EXPECT_NEAR(y.y, x.y - x.x / 2, 1e-14);
  }
}

TEST(Characteristics, AWalkAlongAnEdgeOrThroughVerticesNeitherStallsNorStops) {
  const Square s;
  // Along the horizontal grid line y = 0.5, from the middle of an edge on it, through its vertices.
  const std::vector<double> along = s.interpolate([](Point) { return 1.0; }, [](Point) { return 0.0; });
  const Characteristics c_along(s.side, uniform_term(along, -0.5));
  // Along the cells' diagonals (direction (1, 1)), through the grid's vertices.
  const std::vector<double> diagonal = s.interpolate([](Point) { return 1.0; }, [](Point) { return 1.0; });
  const Characteristics c_diagonal(s.side, uniform_term(diagonal, -0.35));
  int edges = 0, diagonals = 0;
  for (int k = 0; k < s.side.mesh().size(); ++k) {
    Point p[3];
    s.side.mesh().corners(k, p);
    const Point mid = from_reference(p, {0.5, 0});  // the middle of the edge from corner 0 to corner 1
    if (p[0].y == 0.5 && p[1].y == 0.5 && mid.x > 0.6) {
      const Foot f = c_along.trace(k, {0.5, 0});
      const Point y = s.where(f);
      EXPECT_FALSE(f.at_boundary);
      EXPECT_NEAR(y.x, mid.x - 0.5, 1e-14);
      EXPECT_NEAR(y.y, 0.5, 1e-14);
      ++edges;
    }
    const bool on_diagonal = std::fabs((p[1].x - p[0].x) - (p[1].y - p[0].y)) < 1e-12 && p[1].x > p[0].x + 0.05;
    if (on_diagonal && mid.x > 0.4 && mid.y > 0.4) {
      const Foot f = c_diagonal.trace(k, {0.5, 0});
      const Point y = s.where(f);
      EXPECT_FALSE(f.at_boundary);
      EXPECT_NEAR(y.x, mid.x - 0.35, 1e-14);
      EXPECT_NEAR(y.y, mid.y - 0.35, 1e-14);
      ++diagonals;
    }
  }
  EXPECT_GE(edges, 3);
  EXPECT_GE(diagonals, 20);
}

TEST(Characteristics, AWalkAlongTheEdgesOfATurnedGridDoesNotBounceBetweenTheirTriangles) {
  const double angle = 0.3;
  const Square s(angle);
  const Point e{std::cos(angle), std::sin(angle)};  // the direction of the turned grid's lines j = const
  const std::vector<double> along = s.interpolate([&](Point) { return e.x; }, [&](Point) { return e.y; });
  const Characteristics c(s.side, uniform_term(along, -0.55));
  CharacteristicsReport report;
  int edges = 0;
  for (int k = 0; k < s.side.mesh().size(); ++k) {
    Point p[3];
    s.side.mesh().corners(k, p);
    const Point d = p[1] - p[0];
    if (std::fabs(cross(d, e)) > 1e-12 || dot(d, e) < 0) continue;  // corner 0 to corner 1 along e
    const Point mid = from_reference(p, {0.5, 0});
    const double along_line = dot(mid, e), across = cross(e, mid);  // the grid's coordinates (i/10, j/10)
    if (along_line < 0.6 || across < 0.05) continue;                // not the bottom line: a boundary
    const Foot f = c.trace(k, {0.5, 0}, &report);
    const Point y = s.where(f);
    EXPECT_FALSE(f.at_boundary);
    EXPECT_NEAR(y.x, mid.x - 0.55 * e.x, 1e-14);
    EXPECT_NEAR(y.y, mid.y - 0.55 * e.y, 1e-14);
    ++edges;
  }
  EXPECT_GE(edges, 30);
  EXPECT_LT(report.crossings, 12 * edges);  // measured 10: 5.5 cells, and around each vertex on the line
}

TEST(Characteristics, NoVelocityGivesTheMassMatrixTimesTheField) {
  const Square s;
  const std::vector<double> zero(2 * s.mesh.vertices.size(), 0.0);
  const std::vector<double> f =
      s.interpolate([](Point x) { return 1 + 2 * x.x + 3 * x.y; }, [](Point x) { return 4 - x.x * x.y; });
  CharacteristicsTerm term = uniform_term(zero, -0.3);
  term.field = f.data();
  term.c = 2.5;
  std::vector<double> b(f.size());
  Characteristics(s.side, term).assemble(b.data());
  const std::vector<double> reference = s.mass_times(f);
  for (size_t i = 0; i < b.size(); ++i) EXPECT_NEAR(b[i], 2.5 * reference[i], 1e-15) << "row " << i;
}

TEST(Characteristics, AUniformVelocityGivesTheMassMatrixTimesTheShiftedField) {
  const Square s;
  const Point w{0.3, 0.2};
  const double dt = -0.1;  // the feet are x - (0.03, 0.02)
  const std::vector<double> velocity = s.interpolate([&](Point) { return w.x; }, [&](Point) { return w.y; });
  auto f0 = [](Point x) { return 1 + 2 * x.x + 3 * x.y; };
  auto f1 = [](Point x) { return 4 - x.x + 0.5 * x.y; };
  const std::vector<double> f = s.interpolate(f0, f1);
  CharacteristicsTerm term = uniform_term(velocity, dt);
  term.field = f.data();
  std::vector<double> b(f.size());
  CharacteristicsReport report;
  Characteristics(s.side, term).assemble(b.data(), &report);
  // f o X is linear where the feet stay inside: the P1 interpolant of the shifted field is exact there.
  auto shift = [&](Point x) { return Point{x.x + dt * w.x, x.y + dt * w.y}; };
  const std::vector<double> g =
      s.interpolate([&](Point x) { return f0(shift(x)); }, [&](Point x) { return f1(shift(x)); });
  const std::vector<double> reference = s.mass_times(g);
  int rows = 0;
  for (size_t v = 0; v < s.mesh.vertices.size(); ++v) {
    const Point x = s.mesh.vertices[v];
    if (x.x < 0.15 || x.y < 0.15) continue;  // support reaching within 0.03 of the inflow sides
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(b[2 * v + c], reference[2 * v + c], 1e-15) << "vertex " << v;
    ++rows;
  }
  EXPECT_EQ(rows, 81);
  EXPECT_GT(report.boundary_stops, 0);  // the walks from near x = 0 and y = 0 did stop
  EXPECT_EQ(report.points, 7L * s.mesh.size());
}

TEST(Characteristics, AScalarFieldCarriedByAVelocityOfAnotherSpace) {
  // A scalar P1 field on the square, the velocity a uniform [P1, P1] field of its own side: the P1 mass matrix
  // times the shifted linear field on the rows whose support's feet stay inside, as for one space.
  const Square s;
  const test::P1 scalar(s.mesh);
  const FluidSide field_side(s.mesh, scalar, {0});
  const Point w{-0.2, 0.4};
  const double dt = -0.1;  // the feet are x + (0.02, -0.04)
  const std::vector<double> velocity = s.interpolate([&](Point) { return w.x; }, [&](Point) { return w.y; });
  auto f = [](Point x) { return 2 - x.x + 3 * x.y; };
  std::vector<double> values(s.mesh.vertices.size()), shifted(values.size());
  for (size_t v = 0; v < values.size(); ++v) {
    const Point x = s.mesh.vertices[v];
    values[v] = f(x);
    shifted[v] = f({x.x + dt * w.x, x.y + dt * w.y});
  }
  CharacteristicsTerm term;
  term.velocity = velocity.data();
  term.field = values.data();
  term.components = {0};
  term.dt = dt;
  std::vector<double> b(values.size());
  Characteristics(field_side, term, &s.side).assemble(b.data());
  // the reference: the scalar mass matrix times the shifted values (component 0 of the vector helper)
  std::vector<double> both(2 * values.size(), 0.0);
  for (size_t v = 0; v < values.size(); ++v) both[2 * v] = shifted[v];
  const std::vector<double> reference = s.mass_times(both);
  int rows = 0;
  for (size_t v = 0; v < values.size(); ++v) {
    const Point x = s.mesh.vertices[v];
    if (x.x > 0.85 || x.y < 0.15) continue;  // support reaching the outflow sides' feet
    EXPECT_NEAR(b[v], reference[2 * v], 1e-15) << "vertex " << v;
    ++rows;
  }
  EXPECT_EQ(rows, 81);
  // a velocity side on another mesh is refused
  const Mesh other = test::grid_mesh(10, 10, 0, 0, 1, 2);
  const test::VectorP1 other_space(other);
  const FluidSide other_side(other, other_space, {0, 1});
  EXPECT_THROW(Characteristics(field_side, term, &other_side), Error);
}

TEST(Characteristics, BadInputIsNamed) {
  const Square s;
  std::vector<double> w = s.interpolate([](Point) { return 1.0; }, [](Point) { return 0.0; });
  w[2 * 60] = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> b(w.size());
  try {
    Characteristics(s.side, uniform_term(w, -0.1)).assemble(b.data());
    FAIL() << "a NaN velocity was traced";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the velocity is not finite in fluid triangle"), std::string::npos)
        << e.what();
  }
  const std::vector<double> ok = s.interpolate([](Point) { return 1.0; }, [](Point) { return 0.0; });
  CharacteristicsTerm term = uniform_term(ok, std::numeric_limits<double>::infinity());
  EXPECT_THROW(Characteristics(s.side, term), Error);
  term = uniform_term(ok, -0.1);
  term.components = {0, 2};
  EXPECT_THROW(Characteristics(s.side, term), Error);
  term = uniform_term(ok, -0.1);
  term.v_component = 0;
  EXPECT_THROW(Characteristics(s.side, term), Error);
  // Towards a point inside a triangle for a very long time: each straight stretch overshoots it, and the walk
  // zigzags across it.
  const std::vector<double> sink =
      s.interpolate([](Point x) { return 0.53 - x.x; }, [](Point x) { return 0.47 - x.y; });
  try {
    Characteristics(s.side, uniform_term(sink, 1e12)).assemble(b.data());
    FAIL() << "an endless walk was not stopped";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("crossed more than 100000 edges"), std::string::npos) << e.what();
  }
}
