// Property / fuzz test of the clipper, the fluid search and the coupling assembly.
//
// DLMFSI_FUZZ_PAIRS (default 1000000) triangle pairs, drawn in turn from nine families of random and
// adversarial configurations (random; snapped to coarse grids; rotated and translated mesh cells; points on
// edges by exact dyadic combinations; 1e-15 perturbations of those; slivers of aspect ratio 1e12; huge and
// tiny coordinates; identical, mirrored and edge-sharing copies). For every pair:
//  - both pieces clip(a, b) and clip(b, a) are finite, have 0 or 3..6 vertices, are convex and
//    counter-clockwise up to the rounding of constructed vertices (piece_check.hpp);
//  - area(clip(a, b)) == area(clip(b, a)), and <= min(area a, area b);
//  - tiling: a is split into three triangles about an interior point (the configuration of fluid triangles
//    sharing edges); their pieces against b add up to area(clip(a, b)); the same with b split;
//  - against an independent reference: CGAL's exact kernel on a sample of every family (more when
//    DLMFSI_FUZZ_EXACT is larger), a long-double Sutherland-Hodgman clipper on every generic random pair.
// All area errors are measured against the tolerance 1e-13 * M * D (M the largest |coordinate| of the
// pair, D the diameter of its bounding box): for triangles of unit shape about the origin this is 1e-13
// relative to their area, and it is the round-off floor of double output vertices for slivers and far
// translated triangles (a constructed vertex is rounded by about eps * M). For well-shaped pairs the error
// relative to the smaller triangle's area is checked against 1e-13 as well.
//
// Then small mesh pairs (DLMFSI_FUZZ_PAIRS / 1000 of them, at least 40): a fluid grid mesh (some with a
// hole, some with jittered vertices) and a solid grid mesh moved by rotations (multiples of 90 degrees or
// random angles) and translations (multiples of the fluid mesh size, so solid vertices land on fluid
// vertices and solid edges on fluid edges, a third of those moved again by 2^-50 of a cell, or random):
//  - the pieces of each solid triangle found by FluidSearch are those of a brute-force scan, and tile it
//    (to 1e-13 relative) where the fluid has no hole;
//  - the pieces inside each fluid triangle of a patch covered by the solid mesh tile that triangle (to
//    1e-13 M D: a jittered fluid triangle can be thin);
//  - assemble_coupling with P1 bases: 1^T B 1 equals the solid area (c1 = 0, c2 = 1), or with a hole and
//    drop_outside the area of the solid inside the fluid, to 1e-13 relative.
// Each test prints its statistics (pairs, worst errors, time).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/clip.hpp"
#include "coupling/coupling.hpp"
#include "mesh/fluid_search.hpp"
#include "geometry/predicates.hpp"
#include "reference.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();  // 2^-52
constexpr double kAreaTol = 1e-13;                                // relative, see the header
constexpr double kTurnTol = 8 * kEps;                             // convexity, see piece_check.hpp

long env_long(const char* name, long fallback) {
  const char* s = std::getenv(name);
  if (!s || !*s) return fallback;
  const double v = std::strtod(s, nullptr);
  return v >= 0 ? static_cast<long>(v) : fallback;
}

using Tri = std::array<Point, 3>;

double tri_area(const Tri& t) { return 0.5 * area2(t[0], t[1], t[2]); }

// Orders t counter-clockwise; false when it is degenerate (exactly).
bool make_ccw(Tri& t) {
  const int o = orient2d(t[0], t[1], t[2]);
  if (o == 0) return false;
  if (o < 0) std::swap(t[1], t[2]);
  return true;
}

bool finite(const Tri& t) {
  for (Point p : t)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  return true;
}

enum Family { kRandom, kSnapped, kMeshCell, kOnEdge, kPerturbed, kSliver, kHugeTiny, kCopies, kFamilies };
const char* const kFamilyName[kFamilies] = {"random", "snapped-to-grid", "mesh-cell-copies", "points-on-edges",
                                            "perturbed-1e-15", "slivers-1e12", "huge-tiny-1e100", "identical-mirrored"};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  // A pair of counter-clockwise, non-degenerate, finite triangles of the family.
  void pair(Family f, Tri& a, Tri& b) {
    for (;;) {
      draw(f, a, b);
      if (finite(a) && finite(b) && make_ccw(a) && make_ccw(b)) return;
    }
  }

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool coin() { return integer(0, 1) == 1; }
  std::mt19937_64& rng() { return rng_; }

 private:
  void draw(Family f, Tri& a, Tri& b) {
    switch (f) {
      case kRandom: random(a, b); break;
      case kSnapped: snapped(a, b); break;
      case kMeshCell: mesh_cell(a, b); break;
      case kOnEdge: on_edge(a, b); break;
      case kPerturbed: perturbed(a, b); break;
      case kSliver: sliver(a, b); break;
      case kHugeTiny: huge_tiny(a, b); break;
      case kCopies: copies(a, b); break;
      default: random(a, b);
    }
  }

  Point rnd() { return {uniform(0, 1), uniform(0, 1)}; }

  void random(Tri& a, Tri& b) {
    for (auto& p : a) p = rnd();
    for (auto& p : b) p = rnd();
    if (integer(0, 3) == 0) {  // far from the origin: the round-off floor grows with |coordinates|
      const Point o{uniform(-1e3, 1e3), uniform(-1e3, 1e3)};
      for (auto& p : a) p = p + o;
      for (auto& p : b) p = p + o;
    }
  }

  // Integer coordinates in [0, g] times a power of two: coincident vertices, shared and collinear edges.
  void snapped(Tri& a, Tri& b) {
    const int g = integer(1, 6);
    const double s = std::ldexp(1.0, integer(-4, 4));
    auto pt = [&] { return Point{s * integer(0, g), s * integer(0, g)}; };
    for (auto& p : a) p = pt();
    for (auto& p : b) p = pt();
  }

  // A cell of an h = 1/8 grid (either diagonal), against a copy of a cell rotated by a multiple of 90 degrees
  // about a grid vertex and translated by multiples of h (vertices on vertices, edges on edges), or rotated
  // by a random angle about one of its vertices (vertex on vertex), or a neighbouring cell.
  void mesh_cell(Tri& a, Tri& b) {
    const double h = 0.125;
    auto cell = [&](int i, int j, int which, Tri& t) {
      const Point p00{i * h, j * h}, p10{(i + 1) * h, j * h}, p01{i * h, (j + 1) * h}, p11{(i + 1) * h, (j + 1) * h};
      switch (which) {
        case 0: t = {p00, p10, p11}; break;
        case 1: t = {p00, p11, p01}; break;
        case 2: t = {p00, p10, p01}; break;
        default: t = {p10, p11, p01};
      }
    };
    cell(integer(0, 3), integer(0, 3), integer(0, 3), b);
    cell(integer(0, 3), integer(0, 3), integer(0, 3), a);
    const int mode = integer(0, 2);
    if (mode == 0) {
      const Point c{h * integer(0, 4), h * integer(0, 4)};
      const int r = integer(0, 3);
      const Point t{h * integer(-2, 2), h * integer(-2, 2)};
      for (auto& p : a) {
        Point d = p - c;
        for (int k = 0; k < r; ++k) d = {-d.y, d.x};
        p = c + d + t;
      }
    } else if (mode == 1) {
      const double th = uniform(0, 2 * std::acos(-1.0));
      const double cs = std::cos(th), sn = std::sin(th);
      const Point c = a[integer(0, 2)];
      const Point target = b[integer(0, 2)];
      for (auto& p : a) {
        const Point d = p - c;
        p = target + Point{cs * d.x - sn * d.y, sn * d.x + cs * d.y};
      }
      a[0] = a[0];  // the rotation centre lands exactly on target (d = 0)
    }  // mode 2: two cells of the same grid (shared edges, shared vertices, disjoint)
  }

  // a with coordinates k/8; vertices of b on a's edge lines at parameters k/8 (exact), on a's vertices, or
  // free: vertex on edge, vertex on vertex, collinear overlapping edges, edge on edge.
  void on_edge(Tri& a, Tri& b) {
    for (auto& p : a) p = {integer(-8, 8) / 8.0, integer(-8, 8) / 8.0};
    for (auto& p : b) {
      const int kind = integer(0, 3);
      if (kind <= 1) {
        const int i = integer(0, 2);
        const double t = integer(-8, 16) / 8.0;
        const Point d = a[(i + 1) % 3] - a[i];
        p = {a[i].x + t * d.x, a[i].y + t * d.y};  // exact: all values have few significant bits
      } else if (kind == 2) {
        p = a[integer(0, 2)];
      } else {
        p = {integer(-8, 8) / 8.0, integer(-8, 8) / 8.0};
      }
    }
    if (coin()) std::swap(a, b);
  }

  // A coincident configuration moved off by 1e-15 (relative) or a few ulps in one to three coordinates.
  void perturbed(Tri& a, Tri& b) {
    const int base = integer(0, 3);
    if (base == 0) snapped(a, b);
    else if (base == 1) mesh_cell(a, b);
    else if (base == 2) on_edge(a, b);
    else copies(a, b);
    const int n = integer(1, 3);
    for (int k = 0; k < n; ++k) {
      Tri& t = coin() ? a : b;
      double& v = coin() ? t[integer(0, 2)].x : t[integer(0, 2)].y;
      if (coin()) {
        v += (coin() ? 1e-15 : -1e-15) * std::max(1.0, std::fabs(v));
      } else {
        const int ulps = integer(1, 4);
        for (int u = 0; u < ulps; ++u) v = std::nextafter(v, coin() ? 2.0 : -2.0);
      }
    }
  }

  // A sliver of aspect ratio about 1e12 (axis-aligned or rotated), against a random triangle, a mesh cell,
  // a sliver sharing its long edge (either side), or a crossing sliver.
  void sliver(Tri& a, Tri& b) {
    auto make = [&](Point p, Point dir, double len, double width, double s, Tri& t) {
      const Point n{-dir.y, dir.x};
      t = {p, p + len * dir, p + (s * len) * dir + width * n};
    };
    const int orient = integer(0, 2);
    Point dir{1, 0};
    if (orient == 1) dir = {0, 1};
    if (orient == 2) {
      const double th = uniform(0, 2 * std::acos(-1.0));
      dir = {std::cos(th), std::sin(th)};
    }
    const double len = uniform(0.5, 1.5);
    const double width = len * 1e-12 * uniform(0.5, 2);
    const Point p{integer(-4, 4) / 8.0, integer(-4, 4) / 8.0};
    make(p, dir, len, width, uniform(0, 1), a);
    switch (integer(0, 3)) {
      case 0:
        for (auto& q : b) q = {uniform(-1, 1.5), uniform(-1, 1.5)};
        break;
      case 1:
        b = {Point{0, 0}, Point{0.5, 0}, Point{0.5, 0.5}};
        for (auto& q : b) q = q + Point{integer(-2, 1) * 0.5, integer(-2, 1) * 0.5};
        break;
      case 2:  // shares the long edge, same or other side
        b = {a[0], a[1], a[0] + uniform(0, 1) * (a[1] - a[0]) + (coin() ? 1 : -1) * width * uniform(0.5, 2) *
                                                                    Point{-dir.y, dir.x}};
        break;
      default: {  // crossing sliver through the middle
        const double th = uniform(-0.1, 0.1);
        const Point d2{dir.x * std::cos(th) - dir.y * std::sin(th), dir.x * std::sin(th) + dir.y * std::cos(th)};
        make(a[0] + 0.5 * len * dir - 0.5 * len * d2, d2, len, width, uniform(0, 1), b);
      }
    }
    if (coin()) std::swap(a, b);
  }

  // Snapped, on-edge or random configurations scaled to about 1e100 or 1e-100, by a power of two (exact)
  // or by 1e100 itself (rounded).
  void huge_tiny(Tri& a, Tri& b) {
    const int base = integer(0, 2);
    if (base == 0) snapped(a, b);
    else if (base == 1) on_edge(a, b);
    else random(a, b);
    const bool huge = coin();
    const bool pow2 = coin();
    const double s = pow2 ? std::ldexp(1.0, huge ? 332 : -332) : (huge ? 1e100 : 1e-100);
    for (auto& p : a) p = s * p;
    for (auto& p : b) p = s * p;
  }

  // Identical (vertex order rotated), mirrored across an edge (shared edge, opposite orientation), sharing
  // an edge on the same side, or inside sharing an edge.
  void copies(Tri& a, Tri& b) {
    for (auto& p : a) p = coin() ? Point{integer(0, 8) / 8.0, integer(0, 8) / 8.0} : rnd();
    if (!make_ccw(a)) return;
    const int i = integer(0, 2);
    const Point p = a[i], q = a[(i + 1) % 3], r = a[(i + 2) % 3];
    switch (integer(0, 3)) {
      case 0: b = {q, r, p}; break;
      case 1: b = {q, p, p + q - r}; break;  // the other triangle of the parallelogram: exact when dyadic
      case 2: {                              // same side, another apex
        const double s = uniform(0.1, 2), t = uniform(0.1, 2);
        b = {p, q, p + s * (r - p) + (0.25 * t) * (q - p)};
        break;
      }
      default: {  // inside, sharing the edge pq: apex a dyadic combination of p, q, r
        const double u = integer(1, 6) / 8.0;
        b = {p, q, Point{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)} + u * (r - Point{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)})};
      }
    }
    if (coin()) std::swap(a, b);
  }

  std::mt19937_64 rng_;
};

// Splits t into three triangles about an interior point (false when the computed point is not strictly
// inside, exactly).
bool fan_split(const Tri& t, Tri out[3]) {
  const Point c{(t[0].x + t[1].x + t[2].x) / 3, (t[0].y + t[1].y + t[2].y) / 3};
  for (int i = 0; i < 3; ++i)
    if (orient2d(t[i], t[(i + 1) % 3], c) <= 0) return false;
  for (int i = 0; i < 3; ++i) out[i] = {t[i], t[(i + 1) % 3], c};
  return true;
}

struct Worst {
  double value = 0;
  std::string where;
  template <class Where>
  void update(double v, Where&& w) {
    if (!(v <= value)) {  // NaN counts as worst
      value = v;
      where = w();
    }
  }
};

std::string describe(long index, Family f, const Tri& a, const Tri& b) {
  char s[512];
  std::snprintf(s, sizeof s, "pair %ld (%s) a = (%.17g, %.17g) (%.17g, %.17g) (%.17g, %.17g), b = (%.17g, %.17g) (%.17g, %.17g) (%.17g, %.17g)",
                index, kFamilyName[f], a[0].x, a[0].y, a[1].x, a[1].y, a[2].x, a[2].y, b[0].x, b[0].y, b[1].x, b[1].y,
                b[2].x, b[2].y);
  return s;
}

}  // namespace

TEST(Property, ClipperOnRandomAndAdversarialPairs) {
  const long pairs = env_long("DLMFSI_FUZZ_PAIRS", 1000000);
  // CGAL exact references: one pair in `stride`, about DLMFSI_FUZZ_EXACT of them (default 16000).
  const long exact_count = std::max(1L, env_long("DLMFSI_FUZZ_EXACT", 16000));
  const long stride = std::max(1L, pairs / exact_count);
  Generator gen(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ_SEED", 20240606)));
  const auto t0 = std::chrono::steady_clock::now();

  Worst sym, bound, tiling, exact_err, sh_err, well_shaped_rel, turn;
  long nonempty[kFamilies] = {}, count[kFamilies] = {}, exact_checked = 0, sh_checked = 0, failures = 0;
  long right_turns = 0, repeated = 0, well_shaped = 0;
  double worst_family[kFamilies] = {};
  auto fail = [&](const std::string& what) {
    if (++failures <= 10) ADD_FAILURE() << what;
  };

  for (long it = 0; it < pairs; ++it) {
    const Family f = static_cast<Family>(it % kFamilies);
    Tri a, b;
    gen.pair(f, a, b);
    ++count[f];
    const double M = ref::max_abs_coordinate(a.data(), b.data());
    const double D = ref::box_diameter(a.data(), b.data());
    const double tol = kAreaTol * M * D;
    auto where = [&] { return describe(it, f, a, b); };

    const Piece pab = clip(a.data(), b.data()), pba = clip(b.data(), a.data());
    for (const Piece* p : {&pab, &pba}) {
      const ref::PieceCheck c = ref::check_piece(*p, M, kTurnTol);
      right_turns += c.exact_right_turns;
      repeated += c.repeated_vertices;
      turn.update(c.worst_right / kEps, where);
      if (!c.error.empty()) fail(c.error + " in " + where());
    }
    const double A = pab.area(), B = pba.area();
    if (!std::isfinite(A) || !std::isfinite(B)) {
      fail("non-finite area in " + where());
      continue;
    }
    if (pab.n > 0) ++nonempty[f];
    auto measure = [&](Worst& w, double err, const char* what) {
      w.update(err / (M * D), where);
      worst_family[f] = std::max(worst_family[f], err / (M * D));
      if (!(err <= tol)) fail(std::string(what) + ": error " + std::to_string(err / (M * D)) + " M D in " + where());
    };
    measure(sym, std::fabs(A - B), "area(clip(a, b)) != area(clip(b, a))");
    const double amin = std::min(tri_area(a), tri_area(b));
    measure(bound, std::max({0.0, A - amin, -A}), "area outside [0, min(area a, area b)]");

    // Tiling: a (then b) split into three triangles sharing edges about an interior point.
    Tri sub[3];
    for (int side = 0; side < 2; ++side) {
      const Tri& whole = side == 0 ? a : b;
      const Tri& other = side == 0 ? b : a;
      if (!fan_split(whole, sub)) continue;
      double sum = 0;
      for (const Tri& s : sub) {
        const Piece p = side == 0 ? clip(s.data(), other.data()) : clip(other.data(), s.data());
        const ref::PieceCheck c = ref::check_piece(p, M, kTurnTol);
          if (!c.error.empty()) fail(c.error + " in a split of " + where());
        sum += p.area();
      }
      measure(tiling, std::fabs(sum - A), "the pieces of a split triangle do not add up");
    }

    // Independent references.
    double reference = -1;
    if (it % stride == 0 || it < kFamilies * 4) {
      reference = ref::exact_intersection_area(a.data(), b.data());
      ++exact_checked;
      measure(exact_err, std::fabs(A - reference), "area differs from CGAL's exact intersection");
    } else if (f == kRandom) {
      reference = static_cast<double>(ref::sutherland_hodgman_area(a.data(), b.data()));
      ++sh_checked;
      measure(sh_err, std::fabs(A - reference), "area differs from the long-double clipper");
    }
    // Well-shaped pairs of comparable size near the origin (both areas at least D^2 / 100, M <= 2 D):
    // relative to the smaller triangle's area.
    if (reference >= 0 && amin >= 0.01 * D * D && M <= 2 * D) {
      ++well_shaped;
      const double rel = std::fabs(A - reference) / amin;
      well_shaped_rel.update(rel, where);
      if (!(rel <= kAreaTol)) fail("relative error " + std::to_string(rel) + " on a well-shaped pair " + where());
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::printf("[property] %ld pairs in %.2f s (%ld checked exactly with %s, %ld with long-double Sutherland-Hodgman, "
              "%ld well-shaped with a reference)\n",
              pairs, seconds, exact_checked, ref::have_exact() ? "CGAL" : "long double (no CGAL)", sh_checked, well_shaped);
  for (int f = 0; f < kFamilies; ++f)
    std::printf("[property]   %-20s %8ld pairs, %8ld with a non-empty piece, worst error %.3g M D\n", kFamilyName[f],
                count[f], nonempty[f], worst_family[f]);
  std::printf("[property] worst errors (units of M D): symmetry %.3g, bound %.3g, split tiling %.3g, vs CGAL %.3g, "
              "vs long double %.3g; relative to area on well-shaped pairs %.3g\n",
              sym.value, bound.value, tiling.value, exact_err.value, sh_err.value, well_shaped_rel.value);
  std::printf("[property] vertices right of an edge line (rounded constructions): %ld, worst %.3g eps M (|e| + 2 |w - v|); "
              "repeated vertices %ld\n",
              right_turns, turn.value, repeated);
  if (!tiling.where.empty()) std::printf("[property] worst tiling: %s\n", tiling.where.c_str());
  if (!exact_err.where.empty()) std::printf("[property] worst vs CGAL: %s\n", exact_err.where.c_str());
  EXPECT_EQ(failures, 0);
}

namespace {

struct Motion {
  double c, s;  // rotation
  Point t;      // then translation
  Point operator()(Point p) const { return {c * p.x - s * p.y + t.x, s * p.x + c * p.y + t.y}; }
};

// The solid mesh moved by m (vertex coordinates computed once, so shared vertices stay shared).
Mesh moved(const Mesh& solid, const Motion& m) {
  Mesh out = solid;
  for (Point& p : out.vertices) p = m(p);
  out.build_adjacency();
  return out;
}

double mesh_area_exact(const Mesh& m) {
  ref::ExactSum s;
  for (int k = 0; k < m.size(); ++k) {
    Point c[3];
    m.corners(k, c);
    s.add(ref::exact_triangle_area(c));
  }
  return s.value();
}

double max_abs(const Mesh& m) {
  double r = 0;
  for (Point p : m.vertices) r = std::max({r, std::fabs(p.x), std::fabs(p.y)});
  return r;
}

// lambda^T B u.
double form(const CsrMatrix& b, const std::vector<double>& lam, const std::vector<double>& u) {
  double s = 0;
  for (int i = 0; i < b.rows; ++i)
    for (int e = b.start[i]; e < b.start[i + 1]; ++e) s += lam[i] * b.value[e] * u[b.column[e]];
  return s;
}

}  // namespace

TEST(Property, MeshPairsTileAndCouplingKeepsTheArea) {
  const long pairs = env_long("DLMFSI_FUZZ_PAIRS", 1000000);
  const long meshes = std::max(40L, pairs / 1000);
  Generator gen(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ_SEED", 20240606)) + 1);
  const auto t0 = std::chrono::steady_clock::now();
  Worst solid_tiling, fluid_tiling, fluid_tiling_md, coupling_rel, solid_tiling_rel;
  long solid_triangles = 0, fluid_triangles = 0, pieces = 0, failures = 0, on_vertices = 0, nudged = 0, holes = 0,
       jitters = 0;
  auto fail = [&](const std::string& what) {
    if (++failures <= 10) ADD_FAILURE() << what;
  };
  const double pi = std::acos(-1.0);

  for (long it = 0; it < meshes; ++it) {
    // Fluid: n x n cells of size h = 1/n on [-1/2, 1/2]^2 (n a power of two: exact vertices), diagonals
    // alternating or not.
    const int n = 1 << gen.integer(2, 4);
    const double h = 1.0 / n;
    Mesh fluid = test::grid_mesh(n, n, -0.5, -0.5, 1, 1, gen.coin());
    // A quarter of the fluid meshes get a hole (a block of cells removed: a non-convex mesh the solid
    // leaves and re-enters, assembled with drop_outside); a third of the others are jittered (interior
    // vertices moved by up to 0.3 h: an unstructured mesh, vertices no longer on the solid's).
    const bool hole = gen.integer(0, 3) == 0;
    const bool jittered = !hole && gen.integer(0, 2) == 0;
    if (hole) {
      const int i0 = gen.integer(n / 2 - 2, n / 2), j0 = gen.integer(n / 2 - 2, n / 2);
      const int w = gen.integer(1, 2), hh = gen.integer(1, 2);
      Mesh holed;
      holed.vertices = fluid.vertices;
      for (int k = 0; k < fluid.size(); ++k) {
        Point c[3];
        fluid.corners(k, c);
        const double cx = (c[0].x + c[1].x + c[2].x) / 3 + 0.5, cy = (c[0].y + c[1].y + c[2].y) / 3 + 0.5;
        if (!(cx > i0 * h && cx < (i0 + w) * h && cy > j0 * h && cy < (j0 + hh) * h)) holed.triangles.push_back(fluid.triangles[k]);
      }
      holed.build_adjacency();
      fluid = holed;
    } else if (jittered) {
      const std::vector<Point> base = fluid.vertices;
      for (double amp = 0.3 * h;; amp /= 2) {
        for (std::size_t v = 0; v < base.size(); ++v) {
          const Point p = base[v];
          const bool boundary = std::fabs(p.x) == 0.5 || std::fabs(p.y) == 0.5;
          fluid.vertices[v] = boundary ? p : p + Point{gen.uniform(-amp, amp), gen.uniform(-amp, amp)};
        }
        bool positive = true;
        for (int k = 0; k < fluid.size() && positive; ++k) positive = orient2d(fluid.vertex(k, 0), fluid.vertex(k, 1), fluid.vertex(k, 2)) > 0;
        if (positive) break;
      }
      fluid.build_adjacency();
    }
    // Solid: m1 x m2 cells of size h or a random size, centred, moved by a rigid motion.
    const bool aligned = gen.integer(0, 2) != 0;  // rotation by k * 90 degrees, translation by multiples of h
    const int m1 = gen.integer(1, n / 2), m2 = gen.integer(1, n / 2);
    const double sw = aligned ? m1 * h : gen.uniform(0.1, 0.45), sh = aligned ? m2 * h : gen.uniform(0.1, 0.45);
    const Mesh solid0 = test::grid_mesh(m1, m2, aligned ? -(m1 / 2) * h : -sw / 2, aligned ? -(m2 / 2) * h : -sh / 2,
                                        sw, sh, gen.coin());
    Motion mo;
    if (aligned) {
      const int r = gen.integer(0, 3);
      mo.c = r == 0 ? 1 : (r == 2 ? -1 : 0);
      mo.s = r == 1 ? 1 : (r == 3 ? -1 : 0);
      const int lim = std::max(0, n / 2 - 1 - std::max(m1, m2) / 2 - 1);
      mo.t = {h * gen.integer(-lim, lim), h * gen.integer(-lim, lim)};
      ++on_vertices;
      if (gen.integer(0, 2) == 0) {  // a third moved again by 2^-50 of a cell: edges 1e-15 apart
        mo.t = mo.t + std::ldexp(h, -50) * Point{gen.uniform(-1, 1), gen.uniform(-1, 1)};
        ++nudged;
      }
    } else {
      const double th = gen.uniform(0, 2 * pi);
      mo.c = std::cos(th);
      mo.s = std::sin(th);
      mo.t = {gen.uniform(-0.15, 0.15), gen.uniform(-0.15, 0.15)};
    }
    const Mesh solid = moved(solid0, mo);
    holes += hole;
    jitters += jittered;
    const double M = std::max(max_abs(solid), max_abs(fluid));

    // 1. Pieces of each solid triangle over the fluid mesh: FluidSearch == brute force, and they tile it.
    FluidGrid grid(fluid);
    FluidSearch search(grid);
    ref::ExactSum covered_by_fluid;
    int hint = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point t[3];
      solid.corners(k, t);
      double sum = 0, brute = 0;
      int found = 0, brute_found = 0;
      search.for_each_piece(t, hint, [&](int, const Piece& p) {
        sum += p.area();
        ++found;
      });
      for (int kf = 0; kf < fluid.size(); ++kf) {
        Point f[3];
        fluid.corners(kf, f);
        const Piece p = clip(t, f);
        if (p.n > 0) {
          brute += p.area();
          ++brute_found;
        }
      }
      if (found != brute_found || std::fabs(sum - brute) > kAreaTol * std::fabs(brute))
        fail("FluidSearch found " + std::to_string(found) + " pieces of area " + std::to_string(sum) + ", brute force " +
             std::to_string(brute_found) + " of area " + std::to_string(brute) + " in mesh pair " + std::to_string(it));
      ++solid_triangles;
      pieces += found;
      covered_by_fluid.add(brute);
      if (hole) continue;  // the pieces tile only the part inside the fluid
      const double want = ref::exact_triangle_area(t);
      const double diam = std::max({std::hypot(t[1].x - t[0].x, t[1].y - t[0].y), std::hypot(t[2].x - t[1].x, t[2].y - t[1].y),
                                    std::hypot(t[0].x - t[2].x, t[0].y - t[2].y)});
      const double err = std::fabs(sum - want);
      solid_tiling.update(err / (M * diam), [&] { return "mesh pair " + std::to_string(it); });
      solid_tiling_rel.update(err / want, [&] { return "mesh pair " + std::to_string(it); });
      if (!(err <= kAreaTol * want)) fail("pieces of solid triangle " + std::to_string(k) + " of mesh pair " + std::to_string(it) +
                                          " do not tile it: relative error " + std::to_string(err / want));
    }

    // 2. Pieces inside each fluid triangle of a patch covered by the (moved) solid mesh tile it.
    //    A fluid triangle counts as covered when its vertices, moved back, are in the solid rectangle: the
    //    closed one when the motion puts solid vertices on fluid vertices (the rectangle is then a union of
    //    fluid cells), else the one shrunk by h / 4 (the moved mesh's boundary is not exactly straight).
    const double lo_x = aligned ? -(m1 / 2) * h : -sw / 2, lo_y = aligned ? -(m2 / 2) * h : -sh / 2;
    const double margin = aligned ? -1e-12 : 0.25 * h;
    for (int kf = 0; kf < fluid.size(); ++kf) {
      Point f[3];
      fluid.corners(kf, f);
      bool covered = true;
      for (Point p : f) {
        const Point d = p - mo.t;
        const Point s{mo.c * d.x + mo.s * d.y, -mo.s * d.x + mo.c * d.y};
        if (!(s.x > lo_x + margin && s.x < lo_x + sw - margin && s.y > lo_y + margin && s.y < lo_y + sh - margin))
          covered = false;
      }
      if (!covered) continue;
      double sum = 0;
      for (int k = 0; k < solid.size(); ++k) {
        Point t[3];
        solid.corners(k, t);
        sum += clip(t, f).area();
      }
      const double want = ref::exact_triangle_area(f);
      const double err = std::fabs(sum - want);
      // In units of M D, the pieces' round-off floor: a jittered fluid triangle can be thin (an area 1e-2 of
      // its diameter squared), where the same absolute round-off is a larger part of the area.
      const double diam = std::max({std::hypot(f[1].x - f[0].x, f[1].y - f[0].y), std::hypot(f[2].x - f[1].x, f[2].y - f[1].y),
                                    std::hypot(f[0].x - f[2].x, f[0].y - f[2].y)});
      fluid_tiling.update(err / want, [&] { return "mesh pair " + std::to_string(it); });
      fluid_tiling_md.update(err / (M * diam), [&] { return "mesh pair " + std::to_string(it); });
      if (!(err <= kAreaTol * M * diam)) fail("pieces inside fluid triangle " + std::to_string(kf) + " of mesh pair " +
                                              std::to_string(it) + " do not tile it: error " + std::to_string(err / (M * diam)) + " M D");
      ++fluid_triangles;
    }

    // 3. Coupling with P1 bases: 1^T B 1 = the solid area.
    test::AffineMap map(solid0, mo.c, -mo.s, mo.s, mo.c, mo.t.x, mo.t.y);
    test::P1 vf(fluid), vs(solid0);
    CouplingOptions opt;
    opt.c1 = 0;
    opt.c2 = 1;
    opt.drop_outside = hole;
    const CsrMatrix B = assemble_coupling(fluid, vf, solid0, vs, map, opt);
    const std::vector<double> one_f(fluid.vertices.size(), 1), one_s(solid0.vertices.size(), 1);
    // the solid area, or with a hole the part inside the fluid (a rigid motion keeps areas: the image's
    // covered area is the reference's, up to the rounding of the moved vertices)
    const double want = hole ? covered_by_fluid.value() : mesh_area_exact(solid0);
    const double rel = std::fabs(form(B, one_s, one_f) - want) / mesh_area_exact(solid0);  // relative to the solid area
    coupling_rel.update(rel, [&] { return "mesh pair " + std::to_string(it); });
    if (!(rel <= kAreaTol)) fail("1^T B 1 != solid area in mesh pair " + std::to_string(it) + ": relative error " + std::to_string(rel));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[property] %ld mesh pairs (%ld moved by multiples of 90 degrees and of h, %ld of them nudged by 2^-50 h; "
              "%ld fluid meshes with a hole, %ld jittered) in %.2f s: %ld solid triangles (%ld pieces), %ld covered "
              "fluid triangles\n",
              meshes, on_vertices, nudged, holes, jitters, seconds, solid_triangles, pieces, fluid_triangles);
  std::printf("[property] worst relative errors: solid tiling %.3g (%.3g M D), fluid tiling %.3g (%.3g M D), 1^T B 1 %.3g\n",
              solid_tiling_rel.value, solid_tiling.value, fluid_tiling.value, fluid_tiling_md.value, coupling_rel.value);
  EXPECT_EQ(failures, 0);
}

// orient2d against GMP rationals on doubles of any exponent (raw bit patterns, subnormals included, no
// NaN or infinity), on nearly collinear triples (c on the line ab up to rounding) at any scale and at
// scales where the products underflow, and on repeated points.
TEST(Property, Orient2dOnAnyFiniteDoubles) {
  const long count = std::max(1000L, env_long("DLMFSI_FUZZ_PAIRS", 1000000) / 20);
  std::mt19937_64 rng(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ_SEED", 20240606)) + 2);
  auto raw = [&] {
    for (;;) {
      std::uint64_t bits = rng();
      double v;
      std::memcpy(&v, &bits, sizeof v);
      if (std::isfinite(v)) return v;
    }
  };
  std::uniform_real_distribution<double> u(-2, 2);
  long mismatches = 0, zeros = 0;
  for (long it = 0; it < count; ++it) {
    Point p[3];
    const int kind = static_cast<int>(it % 5);
    // one scale for the triple; for kind 4 where the products underflow (triangles of size 1e-155 to
    // 1e-170, where the floating-point filter's error bound no longer holds)
    const double s = std::ldexp(1.0, kind == 4 ? -500 - static_cast<int>(rng() % 60) : static_cast<int>(rng() % 2000) - 1000);
    if (kind == 0) {
      for (auto& q : p) q = {raw(), raw()};
    } else if (kind == 1 || kind == 4) {  // one scale, nearly collinear
      p[0] = {s * u(rng), s * u(rng)};
      p[1] = {s * u(rng), s * u(rng)};
      const double t = u(rng);
      p[2] = {p[0].x + t * (p[1].x - p[0].x), p[0].y + t * (p[1].y - p[0].y)};
    } else if (kind == 2) {  // mixed scales: one coordinate raw
      p[0] = {u(rng), u(rng)};
      p[1] = {u(rng), raw()};
      p[2] = {raw(), u(rng)};
    } else {  // repeated point, or a point on an axis-parallel line through another
      p[0] = {raw(), raw()};
      p[1] = {raw(), p[0].y};
      p[2] = rng() % 2 ? p[0] : Point{raw(), p[0].y};
    }
    const int want = ref::exact_orientation(p[0], p[1], p[2]);
    zeros += want == 0;
    if (orient2d(p[0], p[1], p[2]) != want || orient2d_exact(p[0], p[1], p[2]) != want) {
      if (++mismatches <= 5)
        ADD_FAILURE() << "orient2d(" << p[0].x << ", " << p[0].y << ", " << p[1].x << ", " << p[1].y << ", " << p[2].x
                      << ", " << p[2].y << ") = " << orient2d(p[0], p[1], p[2]) << ", exact " << want;
    }
  }
  std::printf("[property] orient2d on %ld triples of any finite doubles (%ld collinear): %ld mismatches\n", count, zeros,
              mismatches);
}
