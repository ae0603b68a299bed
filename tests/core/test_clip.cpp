#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/clip.hpp"
#include "mesh/fluid_search.hpp"
#include "geometry/predicates.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// Independent reference: Sutherland-Hodgman in long double, for generic (non-degenerate) pairs.
long double reference_area(const Point a[3], const Point b[3]) {
  struct P { long double x, y; };
  std::vector<P> poly = {{a[0].x, a[0].y}, {a[1].x, a[1].y}, {a[2].x, a[2].y}};
  for (int j = 0; j < 3 && !poly.empty(); ++j) {
    P p{b[j].x, b[j].y}, q{b[(j + 1) % 3].x, b[(j + 1) % 3].y};
    auto side = [&](P r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
    std::vector<P> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      P r = poly[i], s = poly[(i + 1) % poly.size()];
      long double sr = side(r), ss = side(s);
      if (sr >= 0) out.push_back(r);
      if ((sr > 0 && ss < 0) || (sr < 0 && ss > 0)) {
        long double t = sr / (sr - ss);
        out.push_back({r.x + t * (s.x - r.x), r.y + t * (s.y - r.y)});
      }
    }
    poly = out;
  }
  long double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const P& r = poly[i];
    const P& s = poly[(i + 1) % poly.size()];
    area += r.x * s.y - r.y * s.x;
  }
  return area / 2;
}

void ccw(Point t[3]) {
  if (orient2d(t[0], t[1], t[2]) < 0) std::swap(t[1], t[2]);
}

double tri_area(const Point t[3]) { return 0.5 * area2(t[0], t[1], t[2]); }

// Two random counter-clockwise triangles in the unit square; false for a degenerate draw.
bool random_pair(std::mt19937_64& rng, Point a[3], Point b[3]) {
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 3; ++i) a[i] = {u(rng), u(rng)};
  for (int i = 0; i < 3; ++i) b[i] = {u(rng), u(rng)};
  if (orient2d(a[0], a[1], a[2]) == 0 || orient2d(b[0], b[1], b[2]) == 0) return false;
  ccw(a);
  ccw(b);
  return true;
}

}  // namespace

TEST(Clip, RandomPairsMatchIndependentClipper) {
  std::mt19937_64 rng(7);
  for (int it = 0; it < 100000; ++it) {
    Point a[3], b[3];
    if (!random_pair(rng, a, b)) continue;
    const double got = clip(a, b).area();
    const long double want = reference_area(a, b);
    ASSERT_NEAR(got, static_cast<double>(want), 1e-13) << "pair " << it;
  }
}

TEST(Clip, PiecesAreConvexCounterClockwise) {
  std::mt19937_64 rng(8);
  for (int it = 0; it < 20000; ++it) {
    Point a[3], b[3];
    if (!random_pair(rng, a, b)) continue;
    Piece p = clip(a, b);
    for (int i = 0; i < p.n; ++i)
      ASSERT_GE(orient2d(p.v[i], p.v[(i + 1) % p.n], p.v[(i + 2) % p.n]), 0);
  }
}

// A small triangle a across one edge of b only (the half-plane case): the pieces in b and in b's neighbour
// across that edge match the long-double clipper, tile a, and share the two crossings bit for bit.
TEST(Clip, AcrossOneEdgeTilesWithTheNeighbour) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  int cases = 0;
  for (int it = 0; it < 20000; ++it) {
    const Point p{u(rng), u(rng)}, q{u(rng) + 1, u(rng)}, r{u(rng) + 0.5, u(rng) + 1}, s{u(rng) + 0.5, u(rng) - 1};
    Point b[3] = {p, q, r}, c[3] = {q, p, s};  // b and its neighbour c share the edge p q
    if (orient2d(b[0], b[1], b[2]) <= 0 || orient2d(c[0], c[1], c[2]) <= 0) continue;
    const double t = 0.2 + 0.6 * u(rng), h = 0.05 * u(rng) + 1e-3;
    const Point m{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    Point a[3] = {{m.x + h * (u(rng) - 0.5), m.y + h * (u(rng) - 0.5)}, {m.x + h * (u(rng) - 0.5), m.y + h * (u(rng) - 0.5)},
                  {m.x + h * (u(rng) - 0.5), m.y + h * (u(rng) - 0.5)}};
    if (orient2d(a[0], a[1], a[2]) == 0) continue;
    ccw(a);
    unsigned beyond_b, beyond_c;
    const Piece in_b = clip(a, b, beyond_b), in_c = clip(a, c, beyond_c);
    if (beyond_b != 1u || beyond_c != 1u) continue;  // a reaches beyond edge p q of both, and no other
    ++cases;
    ASSERT_NEAR(in_b.area(), static_cast<double>(reference_area(a, b)), 1e-15) << it;  // coordinates ~1
    ASSERT_NEAR(in_c.area(), static_cast<double>(reference_area(a, c)), 1e-15) << it;
    ASSERT_NEAR(in_b.area() + in_c.area(), tri_area(a), 1e-15) << it;
    int shared = 0;
    for (int i = 0; i < in_b.n; ++i)
      for (int k = 0; k < in_c.n; ++k) shared += in_b.v[i] == in_c.v[k];
    ASSERT_EQ(shared, 2) << it;  // the two crossings, identical doubles
    for (const Piece* piece : {&in_b, &in_c})
      for (int i = 0; i < piece->n; ++i)
        ASSERT_GE(orient2d(piece->v[i], piece->v[(i + 1) % piece->n], piece->v[(i + 2) % piece->n]), 0);
  }
  EXPECT_GT(cases, 10000);
}

// --- a catalogue of degeneracies, each named after its configuration ---

TEST(ClipDegenerate, IdenticalTriangles) {
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}};
  EXPECT_DOUBLE_EQ(clip(a, a).area(), 0.5);
  EXPECT_EQ(clip(a, a).n, 3);
}

TEST(ClipDegenerate, SharedEdgeOppositeSidesIsEmpty) {
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(clip(a, b).n, 0);
  EXPECT_EQ(clip(b, a).n, 0);
}

TEST(ClipDegenerate, SharedEdgeSameSide) {
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{0, 0}, {1, 0}, {0.2, 0.3}};
  EXPECT_NEAR(clip(a, b).area(), 0.15, 1e-16);
}

TEST(ClipDegenerate, TouchingAtOneVertexIsEmpty) {
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{1, 0}, {2, 0}, {2, 1}};
  EXPECT_EQ(clip(a, b).n, 0);
}

TEST(ClipDegenerate, VertexOnEdge) {
  // b's apex lies on a's hypotenuse; b is inside a.
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{0.1, 0.1}, {0.6, 0.1}, {0.5, 0.5}};
  EXPECT_NEAR(clip(a, b).area(), tri_area(b), 1e-16);
  EXPECT_EQ(clip(a, b).n, 3);
}

TEST(ClipDegenerate, CollinearOverlappingEdges) {
  Point a[3] = {{0, 0}, {2, 0}, {0, 2}}, b[3] = {{1, 0}, {3, 0}, {1, 1}};
  // overlap: triangle (1,0), (2,0), (1,1) -> area 0.5
  EXPECT_NEAR(clip(a, b).area(), 0.5, 1e-16);
}

TEST(ClipDegenerate, ContainedTriangleSharingAVertex) {
  Point a[3] = {{0, 0}, {4, 0}, {0, 4}}, b[3] = {{0, 0}, {1, 0}, {0, 1}};
  EXPECT_NEAR(clip(a, b).area(), 0.5, 1e-16);
  EXPECT_NEAR(clip(b, a).area(), 0.5, 1e-16);
}

// a reaches beyond one edge line of b (y = 0) only, but b's corner (1, 0) lies on a's cut edge (along b's
// edge x + y = 1): the corner is a vertex of both pieces, exactly, and they tile a (dyadic coordinates: the
// areas are exact). The one-edge shortcut must leave this case to the general construction.
TEST(ClipDegenerate, OneEdgeCutThroughAFluidCorner) {
  Point a[3] = {{1.125, -0.125}, {0.875, 0.125}, {0.625, 0.125}};
  Point b[3] = {{0, 0}, {1, 0}, {0, 1}}, c[3] = {{1, 0}, {0, 0}, {3, -1}};
  unsigned beyond;
  const Piece in_b = clip(a, b, beyond);
  EXPECT_EQ(beyond, 1u);
  const Piece in_c = clip(a, c);
  auto has = [](const Piece& p, Point v) {
    for (int i = 0; i < p.n; ++i)
      if (p.v[i] == v) return true;
    return false;
  };
  EXPECT_TRUE(has(in_b, {1, 0}));
  EXPECT_TRUE(has(in_c, {1, 0}));
  // b and c share the edge (0, 0) (1, 0) and cover a
  EXPECT_EQ(in_b.area() + in_c.area(), 0.5 * area2(a[0], a[1], a[2]));
  EXPECT_NEAR(in_b.area(), static_cast<double>(reference_area(a, b)), 1e-17);
}

TEST(ClipDegenerate, HexagonFromStarOfDavid) {
  const double pi = std::acos(-1.0);
  Point a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = {std::cos(pi / 2 + 2 * pi * i / 3), std::sin(pi / 2 + 2 * pi * i / 3)};
    b[i] = {-a[i].x, -a[i].y};
  }
  Piece p = clip(a, b);
  EXPECT_EQ(p.n, 6);
  // regular hexagon with circumradius 1/sqrt(3): area 3 sqrt(3)/2 * r^2 = sqrt(3)/2
  EXPECT_NEAR(p.area(), std::sqrt(3.0) / 2, 1e-15);
}

TEST(ClipDegenerate, PerturbationOf1e15) {
  Point a[3] = {{0, 0}, {1, 0}, {0, 1}};
  Point b[3] = {{1 + 1e-15, 0}, {1, 1}, {1e-15, 1}};  // nearly sharing the hypotenuse, from the other side
  const double area = clip(a, b).area();
  EXPECT_GE(area, 0);
  EXPECT_LT(area, 1e-14);
}

// The pieces of a solid triangle over a fluid mesh tile it; the mesh lines pass through its vertices and
// along its edges (the fluid mesh "contains the solid boundary").
TEST(ClipTiling, SolidEdgesOnFluidEdges) {
  Mesh fluid = test::grid_mesh(8, 8, 0, 0, 1, 1);
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  const Point tris[][3] = {{{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}},  // along fluid edges and a diagonal
                           {{0.125, 0.125}, {0.625, 0.125}, {0.125, 0.625}},  // hypotenuse against the diagonals
                           {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}},              // on the domain boundary
                           {{0.1, 0.0}, {0.9, 0.5}, {0.3, 1.0}}};             // vertices on the boundary
  for (const auto& t : tris) {
    double sum = 0;
    int hint = 0;
    search.for_each_piece(t, hint, [&](int, const Piece& p) { sum += p.area(); });
    EXPECT_NEAR(sum, tri_area(t), 1e-15 * 8);
  }
}

// A small triangle far from the origin, clipped relative to its first corner: the same fluid triangles in the
// same order, the same pieces (each corner of t or of a fluid triangle translated exactly, each crossing within
// round-off of the absolute one), and the pieces' areas add up to t's area to round-off of t's size, where in
// absolute coordinates the crossings are rounded to ulp(1000), 1e-6 of t's size. A fluid triangle whose
// corners do not translate exactly (a corner at 0.1, far from the origin 1000) makes the search say so.
TEST(ClipTiling, LocalCoordinatesKeepEveryDecision) {
  const double h = 1e-7;
  Mesh fluid = test::grid_mesh(6, 5, 1000 - 0.3 * h, 2000 - 0.2 * h, 1.7 * h, 1.3 * h, true);
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  const Point t[3] = {{1000 + 0.01 * h, 2000 + 0.02 * h}, {1000 + 0.97 * h, 2000 + 0.11 * h},
                      {1000 + 0.43 * h, 2000 + 1.03 * h}};
  const Point o = t[0];
  const double area = 0.5 * area2(t[0], t[1], t[2]);  // the differences are exact
  std::vector<int> absolute_k, local_k;
  std::vector<Piece> absolute, local;
  int hint = 0;
  search.for_each_piece(t, hint, [&](int k, const Piece& p) {
    absolute_k.push_back(k);
    absolute.push_back(p);
  });
  hint = 0;
  EXPECT_TRUE(search.for_each_piece(t, o, hint, [&](int k, const Piece& p) {
    local_k.push_back(k);
    local.push_back(p);
  }));
  ASSERT_EQ(absolute_k, local_k);
  ASSERT_GT(absolute.size(), 4u);
  double absolute_sum = 0, local_sum = 0;
  for (size_t i = 0; i < absolute.size(); ++i) {
    ASSERT_EQ(absolute[i].n, local[i].n);
    absolute_sum += absolute[i].area();
    local_sum += local[i].area();
    for (int v = 0; v < local[i].n; ++v) {
      const Point a = absolute[i].v[v], l = local[i].v[v];
      bool corner = a == t[0] || a == t[1] || a == t[2];
      for (const Point& p : fluid.vertices) corner = corner || a == p;
      if (corner) {
        EXPECT_TRUE(l == a - o);
      } else {  // a crossing: the absolute one is rounded to ulp(1000) = 1.1e-13
        EXPECT_NEAR(l.x + o.x, a.x, 3e-13);
        EXPECT_NEAR(l.y + o.y, a.y, 5e-13);
      }
    }
  }
  EXPECT_NEAR(local_sum, area, 1e-14 * area);
  EXPECT_GT(std::fabs(absolute_sum - area), 1e-12 * area);  // what the local coordinates mend
  Mesh coarse = test::grid_mesh(1, 1, 0.1, 0.1, 3000, 3000);
  FluidGrid coarse_grid(coarse);
  FluidSearch coarse_search(coarse_grid);
  hint = 0;
  EXPECT_FALSE(coarse_search.for_each_piece(t, o, hint, [](int, const Piece&) {}));
  double sum = 0;
  coarse_search.for_each_piece(t, hint, [&](int, const Piece& p) { sum += p.area(); });
  EXPECT_NEAR(sum, area, 1e-15 * area);  // in absolute coordinates: t inside one fluid triangle, the piece is t
}

TEST(ClipTiling, FluidTrianglePiecesTileTheCoveredPart) {
  // A solid mesh over a fluid triangle: the pieces inside the fluid triangle add up to its area.
  Mesh solid = test::grid_mesh(7, 5, -0.05, -0.03, 1.2, 1.1, true);
  Point f[3] = {{0.1, 0.2}, {0.9, 0.15}, {0.4, 0.95}};
  double sum = 0;
  for (int k = 0; k < solid.size(); ++k) {
    Point s[3];
    solid.corners(k, s);
    sum += clip(s, f).area();
  }
  EXPECT_NEAR(sum, tri_area(f), 1e-15);
}

// The edges a reaches beyond, against the orientations taken one by one; a inside closed b gives a itself.
TEST(Clip, BeyondMarksTheEdgesWithAVertexOutside) {
  std::mt19937_64 rng(17);
  Point a[3], b[3];
  int checked = 0, whole = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    if (!random_pair(rng, a, b)) continue;
    if (trial % 3 == 0)  // a small triangle, often inside b
      for (int i = 0; i < 3; ++i) a[i] = {b[0].x + 0.1 * (a[i].x - 0.5) + 0.3 * (b[1].x - b[0].x),
                                          b[0].y + 0.1 * (a[i].y - 0.5) + 0.3 * (b[2].y - b[0].y)};
    ccw(a);
    unsigned beyond = 0;
    const Piece p = clip(a, b, beyond);
    if (p.n == 0) continue;
    ++checked;
    unsigned expected = 0;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        if (orient2d(b[j], b[(j + 1) % 3], a[i]) < 0) expected |= 1u << j;
    ASSERT_EQ(beyond, expected);
    if (expected == 0) {
      ++whole;
      ASSERT_EQ(p.n, 3);
      for (int i = 0; i < 3; ++i)  // a's own vertices, bit for bit
        EXPECT_TRUE(p.v[0] == a[i] || p.v[1] == a[i] || p.v[2] == a[i]);
    }
    ASSERT_NEAR(p.area(), static_cast<double>(reference_area(a, b)), 1e-13);
  }
  EXPECT_GT(checked, 1000);
  EXPECT_GT(whole, 100);
}

// The advancing front follows only the edges a solid triangle reaches beyond: it must still visit exactly
// the fluid triangles whose clip is non-empty (brute force over the whole mesh), solid vertices on fluid
// vertices and edges included.
TEST(Search, PiecesMatchBruteForceOverTheMesh) {
  Mesh fluid = test::grid_mesh(12, 9, 0, 0, 1.2, 0.9, true);
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.05, 0.85), size(0.001, 0.4);
  std::uniform_int_distribution<int> vertex(0, static_cast<int>(fluid.vertices.size()) - 1);
  int hint = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Point t[3];
    const Point c{u(rng), u(rng)};
    const double s = size(rng);
    for (int i = 0; i < 3; ++i) t[i] = {c.x + s * (u(rng) - 0.45), c.y + s * (u(rng) - 0.45)};
    if (trial % 4 == 0) t[0] = fluid.vertices[vertex(rng)];  // on a fluid vertex
    if (trial % 4 == 1) t[1] = {0.1 * std::floor(10 * c.x), t[1].y};  // on a fluid grid line
    bool inside_square = true;
    for (const Point& p : t) inside_square = inside_square && p.x >= 0 && p.x <= 1.2 && p.y >= 0 && p.y <= 0.9;
    if (!inside_square || orient2d(t[0], t[1], t[2]) == 0) continue;
    ccw(t);
    std::vector<int> found, expected;
    search.for_each_piece(t, hint, [&](int k, const Piece&) { found.push_back(k); });
    for (int k = 0; k < fluid.size(); ++k) {
      Point f[3];
      fluid.corners(k, f);
      if (clip(t, f).n > 0) expected.push_back(k);
    }
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "trial " << trial;
  }
}
