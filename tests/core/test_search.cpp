#include <gtest/gtest.h>

#include <random>

#include "fluid_search.hpp"
#include "predicates.hpp"
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
