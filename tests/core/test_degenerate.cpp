// A catalogue of degenerate configurations for the clipper, the predicates and the fluid search, each
// test named after its configuration and checking exact expected areas (closed forms, or CGAL's exact
// intersection when no closed form is at hand) or tiling invariants:
//  - the pieces of one solid triangle over a fluid mesh tile it (area sum equal to its area to 1e-13
//    relative), and
//  - the pieces inside one fluid triangle over a solid mesh tile the covered part of it.
// Tests named ...Regression reproduce a failure of the core before this catalogue (see the comment there).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geometry/clip.hpp"
#include "mesh/fluid_search.hpp"
#include "geometry/predicates.hpp"
#include "reference.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

using Tri = std::array<Point, 3>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

double area_of(const Tri& t) { return 0.5 * area2(t[0], t[1], t[2]); }

Tri scaled(const Tri& t, double s) { return {s * t[0], s * t[1], s * t[2]}; }

double scale_of(const Tri& a, const Tri& b) {
  return ref::max_abs_coordinate(a.data(), b.data()) * ref::box_diameter(a.data(), b.data());
}

// Checks clip(a, b) and clip(b, a): shape contract, the same area both ways, and the expected area to
// rel * expected + abs_tol_md * M * D. Returns the area.
double expect_pair(const Tri& a, const Tri& b, double expected, double rel = 1e-13, double abs_tol_md = 0) {
  const double M = ref::max_abs_coordinate(a.data(), b.data());
  const double tol = rel * std::fabs(expected) + abs_tol_md * scale_of(a, b);
  const Piece pab = clip(a.data(), b.data()), pba = clip(b.data(), a.data());
  for (const Piece* p : {&pab, &pba}) {
    const ref::PieceCheck c = ref::check_piece(*p, M, 8 * kEps);
    EXPECT_EQ(c.error, "");
  }
  EXPECT_NEAR(pab.area(), expected, tol);
  EXPECT_NEAR(pba.area(), expected, tol);
  return pab.area();
}

// Splits t about an interior point into three triangles sharing edges (fluid triangles around a vertex):
// their pieces against other must add up to area(clip(t, other)).
void expect_split_tiles(const Tri& t, const Tri& other, double abs_tol_md = 1e-13) {
  const Point c{(t[0].x + t[1].x + t[2].x) / 3, (t[0].y + t[1].y + t[2].y) / 3};
  for (int i = 0; i < 3; ++i) ASSERT_GT(orient2d(t[i], t[(i + 1) % 3], c), 0);
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const Tri s{t[i], t[(i + 1) % 3], c};
    sum += clip(s.data(), other.data()).area();
  }
  EXPECT_NEAR(sum, clip(t.data(), other.data()).area(), abs_tol_md * scale_of(t, other));
}

// The pieces of solid triangle t found by FluidSearch over the fluid mesh; their area sum.
double pieces_over(const Mesh& fluid, const Tri& t, int* count = nullptr) {
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  int hint = 0, n = 0;
  double sum = 0;
  search.for_each_piece(t.data(), hint, [&](int, const Piece& p) {
    EXPECT_EQ(ref::check_piece(p, 1, 8 * kEps).error, "");
    sum += p.area();
    ++n;
  });
  if (count) *count = n;
  return sum;
}

// The same by clipping against every fluid triangle.
double brute_force_over(const Mesh& fluid, const Tri& t) {
  double sum = 0;
  for (int k = 0; k < fluid.size(); ++k) {
    Point f[3];
    fluid.corners(k, f);
    sum += clip(t.data(), f).area();
  }
  return sum;
}

const Tri kUnit{Point{0, 0}, Point{1, 0}, Point{0, 1}};

}  // namespace

// ---------------------------------------------------------------- shared edges

// Neighbours of a conforming mesh: the shared edge is traversed in reversed orientation and the triangles
// lie on opposite sides. Their interiors do not meet: no piece, in either order.
TEST(Degenerate, SharedEdgeReversedOrientationIsEmpty) {
  const Tri b{Point{1, 0}, Point{1, 1}, Point{0, 1}};
  EXPECT_EQ(clip(kUnit.data(), b.data()).n, 0);
  EXPECT_EQ(clip(b.data(), kUnit.data()).n, 0);
  // the same along a non-axis edge with non-dyadic coordinates
  const Tri c{Point{0.1, 0.7}, Point{0.3, 0.2}, Point{0.9, 0.6}}, d{Point{0.3, 0.2}, Point{0.1, 0.7}, Point{-0.4, 0.1}};
  ASSERT_GT(orient2d(c[0], c[1], c[2]), 0);
  ASSERT_GT(orient2d(d[0], d[1], d[2]), 0);
  EXPECT_EQ(clip(c.data(), d.data()).n, 0);
  EXPECT_EQ(clip(d.data(), c.data()).n, 0);
}

// Both triangles traverse the shared edge in the same orientation: they lie on the same side and overlap.
TEST(Degenerate, SharedEdgeSameOrientationOverlap) {
  // b = (0,0) (1,0) (1,1): the overlap is (0,0) (1,0) (1/2,1/2), area 1/4
  expect_pair(kUnit, Tri{Point{0, 0}, Point{1, 0}, Point{1, 1}}, 0.25);
  // apex of b inside a: the overlap is b
  const Tri b{Point{0, 0}, Point{1, 0}, Point{0.25, 0.5}};
  expect_pair(kUnit, b, 0.25);
  expect_split_tiles(kUnit, b);
  expect_split_tiles(b, kUnit);
}

TEST(Degenerate, TriangleInsideTriangleSharingAnEdge) {
  const Tri a{Point{0, 0}, Point{4, 0}, Point{0, 4}}, b{Point{0, 0}, Point{4, 0}, Point{1, 1}};
  expect_pair(a, b, 2.0);
  const Piece p = clip(a.data(), b.data());
  EXPECT_EQ(p.n, 3);
  expect_split_tiles(a, b);
  expect_split_tiles(b, a);
  // sharing the edge with non-dyadic coordinates: the piece is b itself, with b's own vertices
  const Tri c{Point{0.1, 0.2}, Point{0.7, 0.3}, Point{0.3, 0.9}};
  const Tri d{c[0], c[1], Point{0.35, 0.4}};
  ASSERT_GT(orient2d(d[0], d[1], d[2]), 0);
  ASSERT_GT(orient2d(c[1], c[2], d[2]), 0);
  ASSERT_GT(orient2d(c[2], c[0], d[2]), 0);
  EXPECT_EQ(clip(c.data(), d.data()).area(), area_of(d));
}

// ---------------------------------------------------------------- vertices on edges and vertices

TEST(Degenerate, VertexOnEdgeFromOutsideIsEmpty) {
  // b's vertex (1/2, 1/2) on a's hypotenuse, b beyond it
  const Tri b{Point{0.5, 0.5}, Point{1, 0.5}, Point{0.5, 1}};
  EXPECT_EQ(clip(kUnit.data(), b.data()).n, 0);
  EXPECT_EQ(clip(b.data(), kUnit.data()).n, 0);
}

TEST(Degenerate, VertexOnEdgeOverlapping) {
  // b's vertex (2, 0) on a's bottom edge; the overlap is (2,0) (4,0) (3,1), area 1
  const Tri a{Point{0, 0}, Point{4, 0}, Point{0, 4}}, b{Point{2, 0}, Point{4, -2}, Point{4, 2}};
  expect_pair(a, b, 1.0);
  expect_split_tiles(a, b);
  expect_split_tiles(b, a);
}

TEST(Degenerate, VertexOnVertexTouchingIsEmpty) {
  for (const Tri& b : {Tri{Point{1, 0}, Point{2, 0}, Point{2, 1}}, Tri{Point{0, 1}, Point{-1, 2}, Point{-1, 1}},
                       Tri{Point{0, 0}, Point{-1, -1}, Point{0, -1}}}) {
    EXPECT_EQ(clip(kUnit.data(), b.data()).n, 0);
    EXPECT_EQ(clip(b.data(), kUnit.data()).n, 0);
  }
}

TEST(Degenerate, VertexOnVertexOverlapping) {
  // a = (0,0) (2,0) (0,2), b = (0,0) (4,2) (2,4): the overlap is (0,0) (4/3,2/3) (2/3,4/3), area 2/3
  const Tri a{Point{0, 0}, Point{2, 0}, Point{0, 2}}, b{Point{0, 0}, Point{4, 2}, Point{2, 4}};
  expect_pair(a, b, 2.0 / 3.0, 4 * kEps);
  expect_split_tiles(a, b);
  expect_split_tiles(b, a);
}

TEST(Degenerate, VertexOnVertexAndEdgeOnEdge) {
  // b's vertices: one of a's vertices, and one inside a's opposite edge: b = (0,0) (1/2,1/2) (0,1)
  // lies in a (it shares two edges' directions), area 1/4
  expect_pair(kUnit, Tri{Point{0, 0}, Point{0.5, 0.5}, Point{0, 1}}, 0.25);
}

// ---------------------------------------------------------------- collinear overlapping edges

TEST(Degenerate, CollinearOverlappingEdgesSameSide) {
  // overlap of (0,0) (2,0) (0,2) with (1,0) (3,0) (1,1): (1,0) (2,0) (1,1), area 1/2
  const Tri a{Point{0, 0}, Point{2, 0}, Point{0, 2}}, b{Point{1, 0}, Point{3, 0}, Point{1, 1}};
  expect_pair(a, b, 0.5);
  expect_split_tiles(a, b);
  expect_split_tiles(b, a);
  // b's edge strictly inside a's edge: b inside a
  expect_pair(a, Tri{Point{0.5, 0}, Point{1.5, 0}, Point{1, 0.5}}, 0.25);
}

TEST(Degenerate, CollinearOverlappingEdgesOppositeSidesIsEmpty) {
  const Tri a{Point{0, 0}, Point{2, 0}, Point{0, 2}}, b{Point{1, 0}, Point{1, -1}, Point{3, 0}};
  ASSERT_GT(orient2d(b[0], b[1], b[2]), 0);
  EXPECT_EQ(clip(a.data(), b.data()).n, 0);
  EXPECT_EQ(clip(b.data(), a.data()).n, 0);
}

TEST(Degenerate, CollinearOverlappingEdgesOnADiagonal) {
  // edges on the line y = x (non-axis): a = (0,0) (1,1) (0,1), b = (1/2,1/2) (3/2,3/2) (1/2,3/2);
  // overlap (1/2,1/2) (1,1) (1/2,1): area 1/8
  expect_pair(Tri{Point{0, 0}, Point{1, 1}, Point{0, 1}}, Tri{Point{0.5, 0.5}, Point{1.5, 1.5}, Point{0.5, 1.5}}, 0.125);
}

// ---------------------------------------------------------------- identical triangles

TEST(Degenerate, IdenticalTriangles) {
  const Tri a{Point{0.1, 0.2}, Point{0.7, 0.3}, Point{0.3, 0.9}};
  for (int r = 0; r < 3; ++r) {
    const Tri b{a[r], a[(r + 1) % 3], a[(r + 2) % 3]};  // the same triangle, vertex order rotated
    const Piece p = clip(a.data(), b.data());
    EXPECT_EQ(p.n, 3);
    EXPECT_EQ(p.area(), clip(b.data(), a.data()).area());
    EXPECT_NEAR(p.area(), ref::exact_triangle_area(a.data()), 2 * kEps * area_of(a));
    for (int i = 0; i < 3; ++i)  // the piece's vertices are a's vertices, bit for bit
      EXPECT_TRUE(std::find_if(p.v, p.v + 3, [&](Point v) { return v == a[i]; }) != p.v + 3);
  }
  expect_split_tiles(a, a);
}

// ---------------------------------------------------------------- slivers (aspect ratio 1e12)

// A sliver whose long edge lies on the fluid grid line y = 0, crossing grid verticals and diagonals: all
// constructed vertices have small y, so the pieces tile it to 1e-13 relative to its own area.
TEST(Degenerate, SliverOnAFluidGridLineTilesIt) {
  const Mesh fluid = test::grid_mesh(8, 8, 0, 0, 1, 1, true);
  const Tri t{Point{0.1, 0}, Point{0.9, 0}, Point{0.37, 0.8e-12}};  // aspect ratio 1e12
  const double want = ref::exact_triangle_area(t.data());
  int count = 0;
  const double got = pieces_over(fluid, t, &count);
  EXPECT_GE(count, 7);
  EXPECT_NEAR(got, want, 1e-13 * want);
  EXPECT_NEAR(brute_force_over(fluid, t), want, 1e-13 * want);
}

// A rotated sliver away from the origin: its crossings with the fluid edges are rounded by about eps M
// across a width of 1e-12, so its own area can only be tiled to about eps M D (here 1e-4 relative): the
// pieces must add up to that round-off floor, not lose or double pieces.
TEST(Degenerate, RotatedSliverTilesItToTheRoundOffFloor) {
  const Mesh fluid = test::grid_mesh(8, 8, 0, 0, 1, 1);
  const double th = 0.3;
  const Point p{0.1, 0.2}, d{std::cos(th), std::sin(th)}, n{-d.y, d.x};
  const Tri t{p, p + 0.8 * d, p + 0.35 * d + 0.8e-12 * n};
  ASSERT_GT(orient2d(t[0], t[1], t[2]), 0);
  const double want = ref::exact_triangle_area(t.data());
  const double M = 1, D = 0.8;
  EXPECT_NEAR(pieces_over(fluid, t), want, 1e-13 * M * D);
  EXPECT_NEAR(brute_force_over(fluid, t), want, 1e-13 * M * D);
  // and against one fluid triangle, the exact intersection
  for (int k = 0; k < fluid.size(); ++k) {
    Point f[3];
    fluid.corners(k, f);
    EXPECT_NEAR(clip(t.data(), f).area(), ref::exact_intersection_area(t.data(), f), 1e-13 * M * D) << k;
  }
}

TEST(Degenerate, SliversSharingTheLongEdge) {
  const Tri a{Point{0, 0}, Point{1, 0}, Point{0.5, 1e-12}};
  // other side: empty; same side, lower apex: b inside a
  EXPECT_EQ(clip(a.data(), Tri{Point{1, 0}, Point{0, 0}, Point{0.5, -1e-12}}.data()).n, 0);
  const Tri b{Point{0, 0}, Point{1, 0}, Point{0.25, 0.5e-12}};
  expect_pair(a, b, ref::exact_intersection_area(a.data(), b.data()), 1e-13);
  EXPECT_NEAR(clip(a.data(), b.data()).area(), area_of(b), 1e-13 * area_of(b));
}

TEST(Degenerate, CrossingSlivers) {
  // two slivers crossing at a small angle: the piece is a tiny quadrilateral
  const Tri a{Point{0, 0}, Point{1, 0}, Point{0.5, 1e-12}};
  const Tri b{Point{0, -1e-9}, Point{1, 1e-9}, Point{0.5, 1e-12}};
  ASSERT_GT(orient2d(b[0], b[1], b[2]), 0);
  const double want = ref::exact_intersection_area(a.data(), b.data());
  EXPECT_GT(want, 0);
  EXPECT_GT(clip(a.data(), b.data()).n, 0);
  expect_pair(a, b, want, 0, 1e-13);
}

// ---------------------------------------------------------------- 1e-15 perturbations

// Neighbours pulled apart by 1e-15 (a gap) or pushed into each other (an overlap of width 1e-15): the
// pieces are empty or tiny and agree with the exact intersection.
TEST(Degenerate, SharedEdgePerturbedBy1e15) {
  for (double delta : {1e-15, -1e-15, 2.2e-16, -2.2e-16}) {
    const Tri b{Point{1 + delta, 0}, Point{1, 1}, Point{delta, 1}};
    const double want = ref::exact_intersection_area(kUnit.data(), b.data());
    expect_pair(kUnit, b, want, 0, 1e-13);
    EXPECT_LE(clip(kUnit.data(), b.data()).area(), 2e-15);
  }
}

TEST(Degenerate, VertexOnEdgePerturbedBy1e15) {
  // b's vertex on a's hypotenuse, moved by +-1e-15 across it
  for (double delta : {1e-15, -1e-15, 0.0}) {
    const Tri b{Point{0.5 + delta, 0.5}, Point{1, 0.5}, Point{0.5, 1}};
    expect_pair(kUnit, b, ref::exact_intersection_area(kUnit.data(), b.data()), 0, 1e-13);
    const Tri c{Point{0.3 + delta, 0.7}, Point{0.9, -0.2}, Point{0.9, 0.9}};  // across the hypotenuse
    expect_pair(kUnit, c, ref::exact_intersection_area(kUnit.data(), c.data()), 0, 1e-13);
  }
}

TEST(Degenerate, CollinearEdgesPerturbedByOneUlp) {
  // the configuration of CollinearOverlappingEdgesSameSide with b's edge tilted by one ulp at either end
  const Tri a{Point{0, 0}, Point{2, 0}, Point{0, 2}};
  for (double y0 : {0.0, 4.9406564584124654e-324, -1e-300, std::nextafter(0.0, 1.0)})
    for (double y1 : {std::nextafter(0.0, 1.0), -std::nextafter(0.0, 1.0), 1e-16, -1e-16}) {
      const Tri b{Point{1, y0}, Point{3, y1}, Point{1, 1}};
      expect_pair(a, b, ref::exact_intersection_area(a.data(), b.data()), 0, 1e-13);
      expect_split_tiles(a, b);
      expect_split_tiles(b, a);
    }
}

// Regression: collinear overlapping edges perturbed by a rounding (here: a dyadic configuration scaled by
// 1e-100). The edges (8.75e-101, 6.25e-101)-(-2.5e-101, 8.75e-101) of a and (1.4375e-100, 5e-101)-
// (-9.53125e-101, 1.03125e-100) of b lie on one line up to rounding and cross properly by the exact
// predicates; the crossing computed from the nearly parallel segments landed on b's end, far outside a,
// and the piece came out 9% too large (0.09 M D). crossing() now clamps to both segments' boxes.
TEST(Degenerate, NearlyCollinearCrossingRegression) {
  const Tri a{Point{8.7500000000000002e-101, 6.2500000000000001e-101}, Point{-2.5e-101, 8.7500000000000002e-101},
              Point{-3.7500000000000001e-101, -2.5e-101}};
  const Tri b{Point{-3.7500000000000001e-101, -2.5e-101}, Point{1.4374999999999999e-100, 5.0000000000000001e-101},
              Point{-9.5312500000000005e-101, 1.0312500000000001e-100}};
  expect_pair(a, b, ref::exact_intersection_area(a.data(), b.data()), 0, 1e-13);
  expect_split_tiles(a, b);
  expect_split_tiles(b, a);
  // the same at unit scale, tilted by one rounding
  const Tri c = scaled(a, 1e100), d = scaled(b, 1e100);
  expect_pair(c, d, ref::exact_intersection_area(c.data(), d.data()), 0, 1e-13);
  // and the crossing itself: on both segments' boxes
  const Point x = crossing(a[0], a[1], b[1], b[2]);
  EXPECT_LE(x.x, std::max(a[0].x, a[1].x));
  EXPECT_GE(x.x, std::min(a[0].x, a[1].x));
}

// Regression: two crossings 4e-15 apart near b's vertex (1, -0.75), which a's edge misses by 2e-16 (a
// 1e-15 perturbation of a vertex-on-vertex configuration). Ordered by floating-point angles about the
// vertices' mean they came out swapped (..., D, A, E, B: a right turn of 9 eps M beyond rounding); the
// order now comes from exact decisions on the input (the direction of the edge leaving each corner), so
// it is the true order ..., D, E, A, B, whatever the rounding of A and E.
TEST(Degenerate, NearlyCoincidentCrossingsOrderRegression) {
  Tri a{Point{1, -0.75}, Point{0.875, -0.5}, Point{-1, 1}};
  Tri b{Point{-0.125, 0.125}, Point{1.0000000000000002, -0.74999999999999978}, Point{0.75, 0.74999999999999978}};
  if (orient2d(a[0], a[1], a[2]) < 0) std::swap(a[1], a[2]);
  if (orient2d(b[0], b[1], b[2]) < 0) std::swap(b[1], b[2]);
  expect_pair(a, b, ref::exact_intersection_area(a.data(), b.data()), 0, 1e-13);
  const Point A{0.99999999999999978, -0.74999999999999944}, E{0.999999999999996, -0.74999999999999645};
  for (const Piece& p : {clip(a.data(), b.data()), clip(b.data(), a.data())}) {
    ASSERT_EQ(p.n, 5);
    EXPECT_EQ(ref::check_piece(p, 1, 4 * kEps).error, "");
    const int e = static_cast<int>(std::find(p.v, p.v + p.n, E) - p.v);
    ASSERT_LT(e, p.n);
    EXPECT_TRUE(p.v[(e + 1) % p.n] == A) << "the corner after E is (" << p.v[(e + 1) % p.n].x << ", " << p.v[(e + 1) % p.n].y << ")";
  }
}

// ---------------------------------------------------------------- huge and tiny coordinates

TEST(Degenerate, HugeAndTinyCoordinates) {
  // catalogue configurations scaled by 2^+-332 (exact) and by 1e+-100 (rounded)
  struct Case {
    Tri a, b;
    double area;
  };
  const Case cases[] = {
      {Tri{Point{0, 0}, Point{2, 0}, Point{0, 2}}, Tri{Point{1, 0}, Point{3, 0}, Point{1, 1}}, 0.5},  // collinear edges
      {Tri{Point{0, 0}, Point{4, 0}, Point{0, 4}}, Tri{Point{2, 0}, Point{4, -2}, Point{4, 2}}, 1.0},  // vertex on edge
      {kUnit, Tri{Point{0, 0}, Point{1, 0}, Point{1, 1}}, 0.25},                                       // shared edge
      {kUnit, Tri{Point{1, 0}, Point{1, 1}, Point{0, 1}}, 0.0},                                        // neighbours
  };
  for (const Case& c : cases)
    for (double s : {std::ldexp(1.0, 332), std::ldexp(1.0, -332), 1e100, 1e-100}) {
      const Tri a = scaled(c.a, s), b = scaled(c.b, s);
      const bool exact = s == std::ldexp(1.0, 332) || s == std::ldexp(1.0, -332);
      const double want = exact ? c.area * s * s : ref::exact_intersection_area(a.data(), b.data());
      expect_pair(a, b, want, 1e-13, 1e-13);
      if (exact) {
        EXPECT_EQ(clip(a.data(), b.data()).area(), want);
      }
      if (want > 0) {
        expect_split_tiles(a, b);
        expect_split_tiles(b, a);
      }
    }
}

// Regression: a coordinate that is subnormal (the next double after 0) beside coordinates of order 1.
// The exact expansion of orient2d multiplies raw coordinates; 4.9e-324 * 0.875 underflows and the sign
// came out wrong, so the piece lost 0.3% of M D. orient2d_exact now falls back to integer arithmetic when
// a product leaves [2^-968, 2^1018].
TEST(Degenerate, SubnormalCoordinateBesideUnitCoordinatesRegression) {
  const Tri a{Point{0.25000000000000011, 0.375}, Point{-0.25, -4.9406564584124654e-324}, Point{0.75, 0.62500000000000044}};
  const Tri b{Point{0.125, 0.25}, Point{-1, 1}, Point{-0.25, 0}};
  Tri ca = a, cb = b;
  if (orient2d(ca[0], ca[1], ca[2]) < 0) std::swap(ca[1], ca[2]);
  if (orient2d(cb[0], cb[1], cb[2]) < 0) std::swap(cb[1], cb[2]);
  expect_pair(ca, cb, ref::exact_intersection_area(ca.data(), cb.data()), 0, 1e-13);
  expect_split_tiles(ca, cb);
  expect_split_tiles(cb, ca);
}

// orient2d on coordinates outside the range where the expansion of products is exact (below 1e-146,
// above 1e146, subnormal, mixed): exact, compared with GMP rationals.
TEST(Degenerate, OrientationOfExtremeCoordinates) {
  const double denorm = std::numeric_limits<double>::denorm_min();
  const double values[] = {0, denorm, -denorm, 3 * denorm, 1e-320, 1e-300, -1e-200, 1e-160, 0.1, 0.875, 1, -2,
                           1e146, 1e200, -1e300, 1.7e308, std::numeric_limits<double>::max()};
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> pick(0, sizeof values / sizeof values[0] - 1);
  for (int it = 0; it < 40000; ++it) {
    Point p[3];
    for (auto& q : p) q = {values[pick(rng)], values[pick(rng)]};
    if (it % 3 == 0) p[2] = p[0];  // repeated points
    if (it % 5 == 0) p[2] = {-p[1].x, -p[1].y};
    ASSERT_EQ(orient2d(p[0], p[1], p[2]), ref::exact_orientation(p[0], p[1], p[2]))
        << p[0].x << " " << p[0].y << " " << p[1].x << " " << p[1].y << " " << p[2].x << " " << p[2].y;
    ASSERT_EQ(orient2d_exact(p[0], p[1], p[2]), ref::exact_orientation(p[0], p[1], p[2]));
  }
  // Regression: nearly collinear points at scale 2^-515 (1e-155): the products underflow and the
  // floating-point filter's bound (3.3e-16 (|l| + |r|)) underflowed with them, so the filter returned -1
  // for a counter-clockwise triple (85 of 2e6 such triples); it now defers to the exact evaluation there.
  {
    const Point a{-0x1.ea2914274f09cp-516, -0x1.b3cbb39ead5bep-515}, b{0x1.c141d03a7a9aep-515, 0x1.49e61413fb22p-518},
        c{-0x1.48c829e424c76p-513, -0x1.24bd10e1f2847p-513};
    EXPECT_EQ(ref::exact_orientation(a, b, c), 1);
    EXPECT_EQ(orient2d(a, b, c), 1);
  }
  // a point one subnormal off the line through two points of order 1
  EXPECT_EQ(orient2d(Point{-1, 0}, Point{1, 0}, Point{0.5, denorm}), 1);
  EXPECT_EQ(orient2d(Point{-1, 0}, Point{1, 0}, Point{0.5, -denorm}), -1);
  EXPECT_EQ(orient2d(Point{-1e300, 0}, Point{1e300, 0}, Point{0.5, denorm}), 1);
}

// Regression: a finite solid triangle far larger than the fluid mesh (corners at +-1e300) that covers it.
// orient2d's exact expansion overflowed (products of 1e300 coordinates), so no piece was found at all;
// and the grid cell of -1e300 was converted to int before clamping (undefined behaviour, UBSan
// float-cast-overflow). The pieces are the fluid triangles themselves, of total area 1.
TEST(Degenerate, FarSolidTriangleOverUnitMeshRegression) {
  const Mesh fluid = test::grid_mesh(4, 4, 0, 0, 1, 1);
  const Tri t{Point{-1e300, -1e300}, Point{1e300, -1e300}, Point{0, 1e300}};
  int count = 0;
  const double got = pieces_over(fluid, t, &count);
  EXPECT_EQ(count, fluid.size());
  EXPECT_DOUBLE_EQ(got, 1.0);
}

// ---------------------------------------------------------------- tiling over meshes

// The solid mesh is the fluid mesh's cells rotated by 90 degrees about a fluid vertex and translated by a
// multiple of the mesh size: solid vertices on fluid vertices, solid edges on fluid edges (the other
// diagonal). Each solid triangle is tiled by its pieces, each covered fluid triangle too.
TEST(Degenerate, SolidVerticesOnFluidVerticesTileBothWays) {
  const Mesh fluid = test::grid_mesh(8, 8, 0, 0, 1, 1, true);
  Mesh solid = test::grid_mesh(4, 2, 0.25, 0.25, 0.5, 0.25);
  for (Point& p : solid.vertices) p = {0.5 - (p.y - 0.5) + 0.125, 0.5 + (p.x - 0.5) - 0.25};  // rotate, shift
  solid.build_adjacency();
  for (int k = 0; k < solid.size(); ++k) {
    Tri t;
    solid.corners(k, t.data());
    EXPECT_EQ(pieces_over(fluid, t), area_of(t)) << k;  // exact: every piece vertex is a mesh vertex
  }
  double covered = 0;
  for (int kf = 0; kf < fluid.size(); ++kf) {
    Point f[3];
    fluid.corners(kf, f);
    double sum = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point s[3];
      solid.corners(k, s);
      sum += clip(s, f).area();
    }
    const double full = 0.5 * area2(f[0], f[1], f[2]);
    EXPECT_TRUE(sum == 0 || std::fabs(sum - full) <= 1e-15 * full) << kf << ": " << sum << " of " << full;
    covered += sum;
  }
  EXPECT_NEAR(covered, 0.5 * 0.25, 1e-15);
}

// A fluid triangle under a rotated solid mesh that covers it: the pieces inside it tile it.
TEST(Degenerate, FluidTriangleUnderRotatedSolidMeshIsTiled) {
  Mesh solid = test::grid_mesh(9, 7, -1, -1, 2, 2, true);
  const double th = 0.7;
  for (Point& p : solid.vertices) p = {std::cos(th) * p.x - std::sin(th) * p.y, std::sin(th) * p.x + std::cos(th) * p.y};
  solid.build_adjacency();
  const Tri fl[] = {Tri{Point{-0.3, -0.2}, Point{0.4, -0.1}, Point{0.1, 0.5}},
                    Tri{Point{0, 0}, Point{0.5, 0}, Point{0, 0.5}},                      // through a solid vertex
                    Tri{Point{-0.5, 0.1}, Point{0.5, 0.1}, Point{0, 0.1 + 1e-12}}};      // a sliver
  for (const Tri& f : fl) {
    ref::ExactSum sum;
    double plain = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point s[3];
      solid.corners(k, s);
      const double a = clip(s, f.data()).area();
      sum.add(a);
      plain += a;
    }
    const double want = ref::exact_triangle_area(f.data());
    // 1e-13 relative; for the sliver (area 5e-13) 1e-16 absolute, below the round-off floor 1e-13 M D
    EXPECT_NEAR(plain, want, 1e-13 * std::max(want, 1e-3));
    EXPECT_NEAR(sum.value(), want, 1e-13 * std::max(want, 1e-3));
  }
}

// Regression: a non-convex fluid mesh (a U: the square [0,3]^2 without the cells of [1,2] x [1,3]) and a
// solid triangle that leaves it through the notch and comes back in: the walk from the centroid's
// triangle stopped at the notch and lost the pieces beyond it (6% of random triangles over this mesh lost
// pieces, the one below 1.7% of its area). FluidSearch now also asks the grid when the walk meets the
// boundary.
TEST(Degenerate, SolidTriangleAcrossANotchOfTheFluidMeshRegression) {
  const Mesh full = test::grid_mesh(6, 6, 0, 0, 3, 3);
  Mesh u;
  u.vertices = full.vertices;
  for (int k = 0; k < full.size(); ++k) {
    Point c[3];
    full.corners(k, c);
    const double cx = (c[0].x + c[1].x + c[2].x) / 3, cy = (c[0].y + c[1].y + c[2].y) / 3;
    if (!(cx > 1 && cx < 2 && cy > 1)) u.triangles.push_back(full.triangles[k]);
  }
  u.build_adjacency();
  const Tri t{Point{2.80888, 0.789596}, Point{2.97117, 1.52994}, Point{0.775713, 1.24568}};
  ASSERT_GT(orient2d(t[0], t[1], t[2]), 0);
  const double brute = brute_force_over(u, t);
  EXPECT_NEAR(pieces_over(u, t), brute, 1e-15);
  // a hole: the square without its middle cells [1,2]^2
  Mesh holed;
  holed.vertices = full.vertices;
  for (int k = 0; k < full.size(); ++k) {
    Point c[3];
    full.corners(k, c);
    const double cx = (c[0].x + c[1].x + c[2].x) / 3, cy = (c[0].y + c[1].y + c[2].y) / 3;
    if (!(cx > 1 && cx < 2 && cy > 1 && cy < 2)) holed.triangles.push_back(full.triangles[k]);
  }
  holed.build_adjacency();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0, 3);
  for (int it = 0; it < 2000; ++it) {
    Tri s{Point{u01(rng), u01(rng)}, Point{u01(rng), u01(rng)}, Point{u01(rng), u01(rng)}};
    if (orient2d(s[0], s[1], s[2]) == 0) continue;
    if (orient2d(s[0], s[1], s[2]) < 0) std::swap(s[1], s[2]);
    ASSERT_NEAR(pieces_over(holed, s), brute_force_over(holed, s), 1e-14) << it;
    ASSERT_NEAR(pieces_over(u, s), brute_force_over(u, s), 1e-14) << it;
  }
}
