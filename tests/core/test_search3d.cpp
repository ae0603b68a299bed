// The 3D fluid search against brute force (every fluid tetrahedron clipped), and the tiling of solid and
// fluid tetrahedra by the pieces, on Kuhn box meshes (plain, jittered, with a hole) and solid meshes moved
// by grid shifts, quarter turns and random rotations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "mesh/fluid_search3d.hpp"
#include "geometry/predicates3d.hpp"
#include "reference3d.hpp"
#include "support3d.hpp"

using namespace dlmfsi;
using dlmfsi::test3d::Tet;

namespace {

// The pieces of t by search, as (fluid tetrahedron, volume), sorted; each fluid tetrahedron at most once.
std::vector<std::pair<int, double>> by_search(FluidSearch3& search, const Point3 t[4], int& hint) {
  std::vector<std::pair<int, double>> out;
  search.for_each_piece(t, hint, [&](int k, const Piece3& p) { out.push_back({k, p.volume()}); });
  std::sort(out.begin(), out.end());
  return out;
}

// Every fluid tetrahedron clipped by the search's clipper (clip_filtered: the same pieces bit for bit).
std::vector<std::pair<int, double>> by_brute_force(const Mesh3& fluid, const Point3 t[4]) {
  std::vector<std::pair<int, double>> out;
  TetFaces t_faces;
  t_faces.set(t);
  for (int k = 0; k < fluid.size(); ++k) {
    Point3 c[4];
    fluid.corners(k, c);
    unsigned beyond;
    const Piece3 p = clip_filtered(t, t_faces, c, beyond);
    if (p.n > 0) out.push_back({k, p.volume()});
  }
  return out;
}

}  // namespace

TEST(Search3d, LocateMatchesBruteForce) {
  const Mesh3 fluid = test3d::box_mesh(5, 4, 3, {0, 0, 0}, {1, 1, 1}, 0.3);
  FluidGrid3 grid(fluid);
  FluidSearch3 search(grid);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  int hint = 0, inside = 0;
  for (int i = 0; i < 3000; ++i) {
    // random points, and vertices and face midpoints of the mesh (on several tetrahedra at once)
    Point3 p{u(rng), u(rng), u(rng)};
    if (i % 3 == 1) p = fluid.vertices[rng() % fluid.vertices.size()];
    const int k = search.locate(p, i % 2 ? hint : static_cast<int>(rng() % fluid.size()));
    bool contained = false;
    for (int t = 0; t < fluid.size() && !contained; ++t) {
      Point3 c[4];
      fluid.corners(t, c);
      bool in = true;
      for (int f = 0; f < 4 && in; ++f) {
        Point3 d[4] = {c[0], c[1], c[2], c[3]};
        d[f] = p;
        in = orient3d(d[0], d[1], d[2], d[3]) >= 0;
      }
      contained = in;
    }
    ASSERT_EQ(k >= 0, contained) << i;
    if (k >= 0) {
      Point3 c[4];
      fluid.corners(k, c);
      for (int f = 0; f < 4; ++f) {
        Point3 d[4] = {c[0], c[1], c[2], c[3]};
        d[f] = p;
        ASSERT_GE(orient3d(d[0], d[1], d[2], d[3]), 0);
      }
      hint = k;
      ++inside;
    }
  }
  EXPECT_GT(inside, 1000);
}

TEST(Search3d, PiecesMatchBruteForce) {
  // plain, jittered and holed fluid meshes; random solid tetrahedra of several sizes, inside, across the
  // boundary and across the hole
  const Mesh3 plain = test3d::box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1});
  const Mesh3 jittered = test3d::box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1}, 0.35, 7);
  const Mesh3 holed = test3d::with_hole(plain, {0.5, 0.5, 0.5}, 0.3);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-0.2, 1.2), size(0.02, 0.6);
  long pieces = 0;
  for (const Mesh3* fluid : {&plain, &jittered, &holed}) {
    FluidGrid3 grid(*fluid);
    FluidSearch3 search(grid);
    int hint = 0;
    for (int i = 0; i < 300; ++i) {
      const Point3 c{u(rng), u(rng), u(rng)};
      const double s = size(rng);
      Tet t;
      for (auto& p : t) p = c + s * Point3{u(rng), u(rng), u(rng)};
      if (i % 5 == 0) t = {Point3{0, 0, 0}, Point3{0.25, 0, 0}, Point3{0, 0.25, 0}, Point3{0, 0, 0.25}};  // on the grid
      if (!test3d::make_positive(t)) continue;
      const auto found = by_search(search, t.data(), hint);
      const auto brute = by_brute_force(*fluid, t.data());
      ASSERT_EQ(found, brute) << "solid tetrahedron " << i;
      pieces += static_cast<long>(found.size());
    }
  }
  EXPECT_GT(pieces, 3000);
}

TEST(Search3d, SolidTetrahedraAreTiledByTheirPieces) {
  // Solid meshes over a fluid box that covers them: shifted by grid steps (vertices on vertices, faces on
  // faces), by half steps, turned a quarter about z (exact), and rotated at random: for every solid
  // tetrahedron the pieces add up to its volume, and over all of them to the solid's volume.
  const Mesh3 fluid = test3d::box_mesh(6, 6, 6, {-0.5, -0.5, -0.5}, {2, 2, 2});
  FluidGrid3 grid(fluid);
  FluidSearch3 search(grid);
  const Mesh3 base = test3d::box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1});
  const Mesh3 jitter = test3d::box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1}, 0.3, 9);
  const Mesh3 solids[] = {base,
                          test3d::moved(base, {0, 0, 1}, 0, {0, 0, 0}, {1.0 / 3, 0, -1.0 / 3}),
                          test3d::moved(base, {0, 0, 1}, 0, {0, 0, 0}, {1.0 / 6, 1.0 / 6, 1.0 / 6}),
                          test3d::quarter_turn(base, {0.5, 0.5, 0.5}),
                          test3d::moved(base, {1, 2, 3}, 0.7, {0.5, 0.5, 0.5}, {0, 0, 0}),
                          test3d::moved(jitter, {-1, 0.5, 2}, 2.1, {0.5, 0.5, 0.5}, {0.01, -0.02, 0.03})};
  for (const Mesh3& solid : solids) {
    int hint = 0;
    double worst = 0, total = 0, exact_total = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point3 t[4];
      solid.corners(k, t);
      double sum = 0;
      search.for_each_piece(t, hint, [&](int, const Piece3& p) { sum += p.volume(); });
      const double v = ref::exact_tet_volume(t[0], t[1], t[2], t[3]);
      worst = std::max(worst, std::fabs(sum - v) / v);
      total += sum;
      exact_total += v;
    }
    EXPECT_LE(worst, 1e-13);
    EXPECT_NEAR(total, exact_total, 1e-13 * exact_total);
  }
}

TEST(Search3d, FluidTetrahedraAreTiledByThePiecesInThem) {
  // a fluid tetrahedron well inside the solid is the union of the solid's pieces in it
  const Mesh3 fluid = test3d::box_mesh(3, 3, 3, {0.25, 0.25, 0.25}, {0.5, 0.5, 0.5}, 0.2, 5);
  FluidGrid3 grid(fluid);
  FluidSearch3 search(grid);
  const Mesh3 solid = test3d::moved(test3d::box_mesh(5, 5, 5, {-0.1, -0.1, -0.1}, {1.2, 1.2, 1.2}), {1, 1, 0}, 0.4,
                                    {0.5, 0.5, 0.5}, {0, 0, 0});
  std::vector<double> covered(fluid.size(), 0.0);
  int hint = 0;
  for (int k = 0; k < solid.size(); ++k) {
    Point3 t[4];
    solid.corners(k, t);
    search.for_each_piece(t, hint, [&](int f, const Piece3& p) { covered[f] += p.volume(); });
  }
  double worst = 0;
  for (int f = 0; f < fluid.size(); ++f) {
    Point3 c[4];
    fluid.corners(f, c);
    const double v = ref::exact_tet_volume(c[0], c[1], c[2], c[3]);
    worst = std::max(worst, std::fabs(covered[f] - v) / v);
  }
  EXPECT_LE(worst, 1e-13);
}
