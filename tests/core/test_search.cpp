#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>

#include "mesh/fluid_search.hpp"
#include "geometry/predicates.hpp"
#include "support.hpp"

using namespace dlmfsi;

static bool inside(const Mesh& m, int k, Point p) {
  for (int e = 0; e < 3; ++e)
    if (orient2d(m.vertex(k, e), m.vertex(k, (e + 1) % 3), p) < 0) return false;
  return true;
}

TEST(Search, LocateFindsAContainingTriangleFromAnyHint) {
  Mesh fluid = test::grid_mesh(20, 13, -1, 0, 3, 2, true);
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(-1, 2), uy(0, 2);
  std::uniform_int_distribution<int> hint(0, fluid.size() - 1);
  for (int i = 0; i < 20000; ++i) {
    Point p{ux(rng), uy(rng)};
    if (i % 4 == 0) p = fluid.vertices[i % fluid.vertices.size()];  // exactly on vertices
    const int k = search.locate(p, i % 2 ? hint(rng) : -1);
    ASSERT_GE(k, 0);
    ASSERT_TRUE(inside(fluid, k, p));
  }
  EXPECT_EQ(search.locate({3.5, 1}, 0), -1);
  EXPECT_EQ(search.locate({0, -1e-12}, 5), -1);
}

TEST(Search, AdjacencyIsSymmetric) {
  Mesh m = test::grid_mesh(6, 4, 0, 0, 1, 1, true);
  int boundary = 0;
  for (int k = 0; k < m.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const int nb = m.neighbours[k][i];
      if (nb < 0) {
        ++boundary;
        continue;
      }
      int back = 0;
      for (int j = 0; j < 3; ++j) back += m.neighbours[nb][j] == k;
      EXPECT_EQ(back, 1);
    }
  EXPECT_EQ(boundary, 2 * (6 + 4));
}

TEST(Search, ClockwiseTriangleIsRejected) {
  Mesh m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}};
  m.triangles = {{0, 2, 1}};
  EXPECT_THROW(m.build_adjacency(), std::runtime_error);
}

TEST(Search, PiecesOfAPartlyOutsideTriangleCoverOnlyTheInside) {
  Mesh fluid = test::grid_mesh(10, 10, 0, 0, 1, 1);
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  // centroid outside the fluid square: the grid fallback finds the pieces
  Point t[3] = {{0.9, 0.5}, {1.6, 0.4}, {1.5, 0.9}};
  double sum = 0;
  int hint = 0, count = 0;
  search.for_each_piece(t, hint, [&](int, const Piece& p) {
    sum += p.area();
    ++count;
  });
  EXPECT_GT(count, 0);
  // inside part: clip against the square [0,1]^2 -> polygon (0.9,0.5), (1,0.4857..), (1,0.58)
  const double y1 = 0.5 + (0.4 - 0.5) * (0.1 / 0.7), y2 = 0.5 + (0.9 - 0.5) * (0.1 / 0.6);
  EXPECT_NEAR(sum, 0.5 * 0.1 * (y2 - y1), 1e-15);
}

// The fluid side renumbers the mesh along a Morton curve: the same triangles (corners in the same local
// order), vertices in order of first use, the neighbours rebuilt through the renumbering equal to the
// adjacency of the renumbered mesh built from scratch.
TEST(Search, RenumberedMeshKeepsTrianglesAndAdjacency) {
  Mesh fluid = test::grid_mesh(9, 7, -1, 0, 3, 2, true);
  const std::vector<int> order = morton_order(fluid);
  ASSERT_EQ(static_cast<int>(order.size()), fluid.size());
  std::vector<int> seen(fluid.size(), 0);
  for (int k : order) ++seen[k];
  for (int s : seen) ASSERT_EQ(s, 1);  // a permutation
  const Mesh r = renumbered(fluid, order);
  ASSERT_EQ(r.vertices.size(), fluid.vertices.size());
  for (int i = 0; i < r.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(r.vertex(i, c) == fluid.vertex(order[i], c));
  int next = 0;  // vertices numbered in order of first use
  for (const auto& t : r.triangles)
    for (int v : t)
      if (v == next) ++next;
      else ASSERT_LT(v, next);
  Mesh rebuilt = r;
  rebuilt.build_adjacency();
  EXPECT_EQ(rebuilt.neighbours, r.neighbours);
}

namespace {

// Every fluid triangle whose interior meets t, with the area of its piece: clip against each triangle of
// the mesh (brute force), the reference for the search.
std::map<int, double> brute_force_pieces(const Mesh& fluid, const Point t[3]) {
  std::map<int, double> out;
  for (int k = 0; k < fluid.size(); ++k) {
    Point c[3];
    fluid.corners(k, c);
    const Piece p = clip(t, c);
    if (p.n > 0) out[k] = p.area();
  }
  return out;
}

// t counter-clockwise from three points.
std::array<Point, 3> ccw(Point a, Point b, Point c) {
  if (orient2d(a, b, c) < 0) std::swap(b, c);
  return {a, b, c};
}

}  // namespace

// The search's shortcut: when the first fluid triangle k cuts t along one edge line only (no corner of t on
// it, crossing t's edges properly), t's part beyond it is built from the same crossings and handed to the
// neighbour across when that closed triangle holds t's corners beyond the line; otherwise the walk goes on.
// Each configuration, from several hints, against clipping t with every fluid triangle: the same triangles,
// the same areas, and the pieces tile t.
TEST(Search, OneEdgeSplitGivesTheBruteForcePieces) {
  const Mesh fluid = test::grid_mesh(8, 8, 0, 0, 8, 8, true);  // integer corners: the constructions are exact
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  // an interior triangle k and its neighbour across the edge AB opposite corner C; D the neighbour's third corner
  const int k = fluid.size() / 2 + 3, i = 2;
  const int across = fluid.neighbours[k][i];
  ASSERT_GE(across, 0);
  const Point a = fluid.vertex(k, (i + 1) % 3), b = fluid.vertex(k, (i + 2) % 3), c = fluid.vertex(k, i);
  Point d{};
  for (int j = 0; j < 3; ++j)
    if (!(fluid.vertex(across, j) == a) && !(fluid.vertex(across, j) == b)) d = fluid.vertex(across, j);
  const Point m = 0.5 * (a + b), mad = 0.5 * (a + d);
  const Point near_c1 = m + 0.125 * (c - m) + 0.0625 * (a - b), near_c2 = m + 0.125 * (c - m) - 0.0625 * (a - b);
  const struct {
    const char* name;
    std::array<Point, 3> t;
    size_t pieces;  // from the brute force: a check on the configuration itself
  } cases[] = {
      {"the corner beyond AB inside the neighbour", ccw(near_c1, near_c2, m + 0.25 * (d - m)), 2},
      {"the corner beyond AB on the neighbour's edge AD", ccw(near_c1, near_c2, mad), 2},
      {"the corner beyond AB beyond the neighbour's edge AD", ccw(near_c1, near_c2, mad + 0.25 * (mad - b)), 3},
      {"two corners beyond AB inside the neighbour", ccw(m + 0.25 * (c - m), m + 0.25 * (d - m) + 0.125 * (a - b),
                                                         m + 0.25 * (d - m) - 0.125 * (a - b)), 2},
      {"a corner on AB (no split)", ccw(m, m + 0.25 * (c - m) + 0.125 * (a - b), m + 0.25 * (d - m)), 2},
      {"AB through a corner of t and across t (no split)", ccw(a, m + 0.25 * (c - m), m + 0.25 * (d - m)), 2},
  };
  for (const auto& kase : cases) {
    const Point* t = kase.t.data();
    const double area = 0.5 * area2(t[0], t[1], t[2]);
    // the crossings are rounded: areas agree to round-off in units of the coordinates' magnitude (8) times
    // t's diameter
    double diameter = 0;
    for (int e = 0; e < 3; ++e)
      diameter = std::max(diameter, std::hypot(t[e].x - t[(e + 1) % 3].x, t[e].y - t[(e + 1) % 3].y));
    const double tol = 1e-14 * 8 * diameter;
    const std::map<int, double> expected = brute_force_pieces(fluid, t);
    ASSERT_EQ(expected.size(), kase.pieces) << kase.name;
    for (int hint : {-1, k, across, 0}) {
      std::map<int, double> found;
      double sum = 0;
      int h = hint;
      search.for_each_piece(t, h, [&](int kf, const Piece& p) {
        EXPECT_EQ(found.count(kf), 0u) << kase.name << ": fluid triangle " << kf << " visited twice";
        found[kf] = p.area();
        sum += p.area();
      });
      ASSERT_EQ(found.size(), expected.size()) << kase.name << ", hint " << hint;
      for (const auto& [kf, piece_area] : found) {
        ASSERT_EQ(expected.count(kf), 1u) << kase.name << ": fluid triangle " << kf;
        EXPECT_NEAR(piece_area, expected.at(kf), tol) << kase.name << ", hint " << hint;
      }
      EXPECT_NEAR(sum, area, tol) << kase.name << ", hint " << hint;
    }
  }
}
