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
