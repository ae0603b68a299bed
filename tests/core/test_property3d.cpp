// Property / fuzz test of the tetrahedron clipper.
//
// DLMFSI_FUZZ3D_PAIRS (default 2000) pairs of tetrahedra (DLMFSI_FUZZ3D_SEED, default 20240601: another seed,
// other pairs), drawn in turn from families of random and adversarial configurations (random; snapped to coarse
// grids; cells of a Kuhn-split cube grid moved by grid symmetries or rotated about a shared vertex; vertices on
// faces, edges and vertices by exact dyadic combinations; 1e-15 and few-ulp perturbations of those; slivers of
// aspect ratio 1e12; huge and tiny coordinates, 1e-100 to 1e100; identical, mirrored and face-sharing copies). For
// every pair:
//  - the pieces a ∩ b and b ∩ a have a valid shape (support3d.hpp: faces ordered from the exact plane
//    sets, Euler's formula, vertices within round-off of both tetrahedra and of their planes);
//  - vol(a ∩ b) agrees with the exact volume (GMP rationals, reference3d.hpp) and with vol(b ∩ a);
//  - tiling: a split into four tetrahedra about its centroid, then b: the pieces add up to vol(a ∩ b).
// Errors are measured against 1e-13 * M * D^2 (M the largest |coordinate|, D the diameter of the pair's
// bounding box): for tetrahedra of unit shape about the origin, 1e-13 relative to their volume; for
// slivers and far translated pairs, the round-off floor of double output vertices (eps * M each).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "geometry/clip3d.hpp"
#include "coupling/coupling3d.hpp"
#include "mesh/fluid_search3d.hpp"
#include "geometry/predicates3d.hpp"
#include "reference3d.hpp"
#include "support3d.hpp"

using namespace dlmfsi;
using dlmfsi::test3d::Tet;

namespace {

long env_long(const char* name, long fallback) {
  const char* s = std::getenv(name);
  if (!s || !*s) return fallback;
  const double v = std::strtod(s, nullptr);
  return v >= 0 ? static_cast<long>(v) : fallback;
}

enum Family { kRandom, kSnapped, kMeshCell, kOnFace, kPerturbed, kSliver, kHugeTiny, kCopies, kFamilies };
const char* const kFamilyName[kFamilies] = {"random", "snapped-to-grid", "mesh-cells", "on-faces-edges-vertices",
                                            "perturbed-1e-15", "slivers-1e12", "huge-tiny-1e100", "copies"};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  // A pair of positively oriented, non-flat, finite tetrahedra of the family.
  void pair(Family f, Tet& a, Tet& b) {
    for (;;) {
      draw(f, a, b);
      if (test3d::finite(a) && test3d::finite(b) && test3d::make_positive(a) && test3d::make_positive(b)) return;
    }
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool coin() { return integer(0, 1) == 1; }
  Point3 rnd() { return {uniform(0, 1), uniform(0, 1), uniform(0, 1)}; }

  void draw(Family f, Tet& a, Tet& b) {
    switch (f) {
      case kRandom: random(a, b); break;
      case kSnapped: snapped(a, b); break;
      case kMeshCell: mesh_cell(a, b); break;
      case kOnFace: on_face(a, b); break;
      case kPerturbed: perturbed(a, b); break;
      case kSliver: sliver(a, b); break;
      case kHugeTiny: huge_tiny(a, b); break;
      default: copies(a, b);
    }
  }

  void random(Tet& a, Tet& b) {
    for (auto& p : a) p = rnd();
    for (auto& p : b) p = rnd();
    if (integer(0, 3) == 0) {  // far from the origin: the round-off floor grows with |coordinates|
      const Point3 o{uniform(-1e3, 1e3), uniform(-1e3, 1e3), uniform(-1e3, 1e3)};
      for (auto& p : a) p = p + o;
      for (auto& p : b) p = p + o;
    }
  }

  // Integer coordinates in [0, g] times a power of two: coincident vertices, shared faces and edges,
  // coplanar faces, vertices on faces.
  void snapped(Tet& a, Tet& b) {
    const int g = integer(1, 4);
    const double s = std::ldexp(1.0, integer(-4, 4));
    auto pt = [&] { return Point3{s * integer(0, g), s * integer(0, g), s * integer(0, g)}; };
    for (auto& p : a) p = pt();
    for (auto& p : b) p = pt();
  }

  // One of the six Kuhn tetrahedra of cube (i, j, k) of an h = 1/4 grid: the path 0 -> e_p -> e_p + e_q -> 1.
  Tet kuhn(int i, int j, int k, int which) {
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const double h = 0.25;
    double c[3] = {i * h, j * h, k * h};
    Tet t;
    t[0] = {c[0], c[1], c[2]};
    for (int s = 0; s < 3; ++s) {
      c[perms[which][s]] += h;
      t[s + 1] = {c[0], c[1], c[2]};
    }
    return t;
  }

  // Two grid cells (shared faces, edges, vertices, disjoint); or one moved by a grid symmetry (a rotation
  // by 90 degrees about an axis through a grid vertex, a translation by grid steps): vertices on vertices,
  // faces on faces; or rotated by a random angle about one of its vertices placed on a vertex of the other.
  void mesh_cell(Tet& a, Tet& b) {
    b = kuhn(integer(0, 2), integer(0, 2), integer(0, 2), integer(0, 5));
    a = kuhn(integer(0, 2), integer(0, 2), integer(0, 2), integer(0, 5));
    const int mode = integer(0, 2);
    if (mode == 0) {
      const Point3 c{0.25 * integer(0, 3), 0.25 * integer(0, 3), 0.25 * integer(0, 3)};
      const int axis = integer(0, 2), turns = integer(0, 3);
      const Point3 t{0.25 * integer(-1, 1), 0.25 * integer(-1, 1), 0.25 * integer(-1, 1)};
      for (auto& p : a) {
        Point3 d = p - c;
        for (int r = 0; r < turns; ++r) {
          if (axis == 0) d = {d.x, -d.z, d.y};
          else if (axis == 1) d = {d.z, d.y, -d.x};
          else d = {-d.y, d.x, d.z};
        }
        p = c + d + t;
      }
    } else if (mode == 1) {
      // a random rotation (Rodrigues) about a vertex of a, which is moved onto a vertex of b
      Point3 axis{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      const double len = std::sqrt(dot(axis, axis));
      axis = (1 / len) * axis;
      const double th = uniform(0, 6.283185307179586), cs = std::cos(th), sn = std::sin(th);
      const Point3 c = a[integer(0, 3)], target = b[integer(0, 3)];
      for (auto& p : a) {
        const Point3 d = p - c;
        const Point3 r = cs * d + sn * cross(axis, d) + ((1 - cs) * dot(axis, d)) * axis;
        p = p == c ? target : target + r;  // the rotation centre lands exactly on target
      }
    }
  }

  // a with coordinates k/8; vertices of b at exact dyadic combinations of a's vertices: on a face, on an
  // edge (or its line), on a vertex, or free.
  void on_face(Tet& a, Tet& b) {
    for (auto& p : a) p = {integer(-8, 8) / 8.0, integer(-8, 8) / 8.0, integer(-8, 8) / 8.0};
    for (auto& p : b) {
      const int kind = integer(0, 4);
      if (kind <= 1) {  // on a face plane: weights k/8 on three vertices, summing to 1
        const int f = integer(0, 3);
        const int u = integer(-4, 12), v = integer(-4, 12);
        const Point3 q = a[(f + 1) % 4], r = a[(f + 2) % 4], s = a[(f + 3) % 4];
        p = q + (u / 8.0) * (r - q) + (v / 8.0) * (s - q);
      } else if (kind == 2) {  // on an edge line
        const int i = integer(0, 3), j = (i + integer(1, 3)) % 4;
        p = a[i] + (integer(-8, 16) / 8.0) * (a[j] - a[i]);
      } else if (kind == 3) {
        p = a[integer(0, 3)];
      } else {
        p = {integer(-8, 8) / 8.0, integer(-8, 8) / 8.0, integer(-8, 8) / 8.0};
      }
    }
    if (coin()) std::swap(a, b);
  }

  // A coincident configuration moved off by 1e-15 (relative) or a few ulps in one to three coordinates.
  void perturbed(Tet& a, Tet& b) {
    const int base = integer(0, 3);
    if (base == 0) snapped(a, b);
    else if (base == 1) mesh_cell(a, b);
    else if (base == 2) on_face(a, b);
    else copies(a, b);
    const int n = integer(1, 3);
    for (int k = 0; k < n; ++k) {
      Tet& t = coin() ? a : b;
      Point3& p = t[integer(0, 3)];
      const int axis = integer(0, 2);
      double& v = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
      if (coin()) {
        v += (coin() ? 1e-15 : -1e-15) * std::max(1.0, std::fabs(v));
      } else {
        const int ulps = integer(1, 4);
        for (int u = 0; u < ulps; ++u) v = std::nextafter(v, coin() ? 2.0 : -2.0);
      }
    }
  }

  // A flat tetrahedron (height about 1e-12 of its size) or a needle (two dimensions that small), against a
  // random tetrahedron, a grid cell, or a sliver sharing its base (either side).
  void sliver(Tet& a, Tet& b) {
    const Point3 base[3] = {rnd(), rnd(), rnd()};
    const double eps = 1e-12 * uniform(0.5, 2);
    if (coin()) {
      const Point3 n = cross(base[1] - base[0], base[2] - base[0]);
      a = {base[0], base[1], base[2], (1.0 / 3) * (base[0] + base[1] + base[2]) + eps * n};
    } else {
      const Point3 d = base[1] - base[0];
      a = {base[0], base[1], base[0] + 0.5 * d + eps * Point3{-d.y, d.x, 0}, base[0] + 0.3 * d + eps * Point3{0, -d.z, d.y}};
    }
    switch (integer(0, 2)) {
      case 0:
        for (auto& p : b) p = {uniform(-0.5, 1.5), uniform(-0.5, 1.5), uniform(-0.5, 1.5)};
        break;
      case 1:
        b = kuhn(integer(0, 3), integer(0, 3), integer(0, 3), integer(0, 5));
        break;
      default:  // shares the base face, same or other side
        b = {a[0], a[1], a[2], a[3] + (coin() ? 1.0 : -1.0) * uniform(0.5, 2) * (a[3] - a[0])};
    }
    if (coin()) std::swap(a, b);
  }

  // Snapped, on-face or random configurations scaled to about 1e100 or 1e-100, by a power of two (exact)
  // or by 1e100 itself (rounded).
  void huge_tiny(Tet& a, Tet& b) {
    const int base = integer(0, 2);
    if (base == 0) snapped(a, b);
    else if (base == 1) on_face(a, b);
    else random(a, b);
    const bool huge = coin(), pow2 = coin();
    const double s = pow2 ? std::ldexp(1.0, huge ? 332 : -332) : (huge ? 1e100 : 1e-100);
    for (auto& p : a) p = s * p;
    for (auto& p : b) p = s * p;
  }

  // Identical (vertices permuted), mirrored through a face's vertex (shared face, other side), sharing a
  // face on the same side, or inside sharing a face.
  void copies(Tet& a, Tet& b) {
    for (auto& p : a) p = coin() ? Point3{integer(0, 8) / 8.0, integer(0, 8) / 8.0, integer(0, 8) / 8.0} : rnd();
    if (!test3d::make_positive(a)) return;
    const int i = integer(0, 3);
    const Point3 p = a[(i + 1) % 4], q = a[(i + 2) % 4], r = a[(i + 3) % 4], o = a[i];
    const Point3 centre = (1.0 / 3) * (p + q + r);
    switch (integer(0, 3)) {
      case 0: b = {q, r, p, o}; break;
      case 1: b = {p, q, r, centre + (centre - o)}; break;                               // other side
      case 2: b = {p, q, r, o + uniform(-0.5, 0.5) * (q - p) + uniform(0.1, 1) * (o - centre)}; break;  // same side
      default: b = {p, q, r, centre + (integer(1, 7) / 8.0) * (o - centre)};             // inside
    }
    if (coin()) std::swap(a, b);
  }

  std::mt19937_64 rng_;
};

struct Worst {
  double value = 0;
  std::string where;
  void update(double v, const std::string& w) {
    if (!(v <= value)) {  // NaN counts as worst
      value = v;
      where = w;
    }
  }
};

std::string describe(long index, Family f, const Tet& a, const Tet& b) {
  std::string s = "pair " + std::to_string(index) + " (" + kFamilyName[f] + ")";
  char buf[128];
  for (const Tet* t : {&a, &b}) {
    s += t == &a ? " a =" : " b =";
    for (Point3 p : *t) {
      std::snprintf(buf, sizeof buf, " (%.17g, %.17g, %.17g)", p.x, p.y, p.z);
      s += buf;
    }
  }
  return s;
}

}  // namespace

TEST(Property3d, ClipperAgainstExactVolumes) {
  const long pairs = env_long("DLMFSI_FUZZ3D_PAIRS", 2000);
  Generator gen(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ3D_SEED", 20240601)));
  const auto start = std::chrono::steady_clock::now();
  long failures = 0, empty = 0, whole = 0, bad_shape = 0;
  long per_family[kFamilies] = {};
  double family_error[kFamilies] = {};
  Worst exact_error, symmetry_error, tiling_error;
  for (long k = 0; k < pairs; ++k) {
    const Family f = static_cast<Family>(k % kFamilies);
    Tet a, b;
    gen.pair(f, a, b);
    ++per_family[f];
    double m, d;
    test3d::scales(a, b, m, d);
    const double scale = m * d * d;  // volumes' round-off floor, divided by eps
    const Piece3 p = clip(a.data(), b.data()), q = clip(b.data(), a.data());
    const std::string shape = test3d::piece_shape(p, a, b, 64 * 2.2e-16 * m) + test3d::piece_shape(q, b, a, 64 * 2.2e-16 * m);
    if (!shape.empty()) {
      if (++bad_shape <= 5) ADD_FAILURE() << shape << ": " << describe(k, f, a, b);
    }
    empty += p.n == 0;
    whole += p.n == 4;
    bool positive;
    const double exact = ref::exact_intersection_volume(a.data(), b.data(), &positive);
    const double v = p.volume();
    exact_error.update(std::fabs(v - exact) / scale, describe(k, f, a, b));
    family_error[f] = std::max(family_error[f], std::fabs(v - exact) / scale);
    symmetry_error.update(std::fabs(q.volume() - v) / scale, describe(k, f, a, b));
    if ((p.n > 0) != positive && ++failures <= 5)
      ADD_FAILURE() << "empty piece against a positive exact volume or the reverse: " << describe(k, f, a, b);
    Tet as[4], bs[4];
    for (int side = 0; side < 2; ++side) {
      if (!test3d::split4(side == 0 ? a : b, side == 0 ? as : bs)) continue;
      double s = 0;
      for (int i = 0; i < 4; ++i) s += side == 0 ? clip(as[i].data(), b.data()).volume() : clip(a.data(), bs[i].data()).volume();
      tiling_error.update(std::fabs(s - v) / scale, describe(k, f, a, b));
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ property3d ] %ld pairs (%ld empty, %ld whole), %.1f s; worst error / (M D^2): exact %.3g, "
              "symmetry %.3g, tiling %.3g; per family:",
              pairs, empty, whole, seconds, exact_error.value, symmetry_error.value, tiling_error.value);
  for (int f = 0; f < kFamilies; ++f) std::printf(" %s %ld (%.2g)", kFamilyName[f], per_family[f], family_error[f]);
  std::printf("\n");
  EXPECT_LE(exact_error.value, 1e-13) << exact_error.where;
  EXPECT_LE(symmetry_error.value, 1e-13) << symmetry_error.where;
  EXPECT_LE(tiling_error.value, 1e-13) << tiling_error.where;
  EXPECT_EQ(bad_shape, 0);
  EXPECT_EQ(failures, 0);
}

// clip_filtered against clip on the same pairs: the same emptiness, vertex count, plane sets (each
// vertex's, as a sorted list) and beyond; its own vertices within the filtered path's bound of clip's
// vertex on the same planes (2^-40 of the pair's diameter for a crossing, plus round-off), a valid shape,
// and its volume against the exact one as above. Some pieces must take the floating-point path (their
// crossings rounded differently from clip's canonical ones), some the exact one (the degenerate families).
TEST(Property3d, FilteredClipperAgainstExact) {
  const long pairs = env_long("DLMFSI_FUZZ3D_PAIRS", 2000);
  Generator gen(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ3D_SEED", 20240601)) + 1);
  long mismatches = 0, bad_shape = 0, rounded = 0, canonical = 0;
  Worst exact_error, vertex_error;
  for (long k = 0; k < pairs; ++k) {
    const Family f = static_cast<Family>(k % kFamilies);
    Tet a, b;
    gen.pair(f, a, b);
    double m, d;
    test3d::scales(a, b, m, d);
    unsigned beyond_exact = 0, beyond = 0;
    TetFaces a_faces;
    a_faces.set(a.data());
    const Piece3 e = clip(a.data(), b.data(), beyond_exact);
    const Piece3 p = clip_filtered(a.data(), a_faces, b.data(), beyond);
    const std::string where = describe(k, f, a, b);
    const std::string shape = test3d::piece_shape(p, a, b, 64 * 2.2e-16 * m);
    if (!shape.empty() && ++bad_shape <= 5) ADD_FAILURE() << shape << ": " << where;
    bool same = p.n == e.n && (p.n == 0 || beyond == beyond_exact);
    std::vector<int> planes_p(p.planes, p.planes + p.n), planes_e(e.planes, e.planes + e.n);
    std::sort(planes_p.begin(), planes_p.end());
    std::sort(planes_e.begin(), planes_e.end());
    same = same && planes_p == planes_e;
    if (!same && ++mismatches <= 5) ADD_FAILURE() << "not clip's piece (vertices, planes or beyond): " << where;
    if (!same) continue;
    bool identical = true;
    for (int i = 0; i < p.n; ++i)
      for (int j = 0; j < e.n; ++j)
        if (p.planes[i] == e.planes[j]) {
          const Point3 g = p.v[i] - e.v[j];
          const double off = std::max({std::fabs(g.x), std::fabs(g.y), std::fabs(g.z)});
          identical = identical && off == 0;
          vertex_error.update(off / (0x1p-40 * d + 64 * 2.2e-16 * m), where);
        }
    if (p.n > 0) ++(identical ? canonical : rounded);
    bool positive;
    const double exact = ref::exact_intersection_volume(a.data(), b.data(), &positive);
    exact_error.update(std::fabs(p.volume() - exact) / (m * d * d), where);
  }
  std::printf("[ property3d ] filtered clipper: %ld pairs, %ld pieces with rounded crossings, %ld as clip's; worst "
              "vertex offset / bound %.3g, volume error / (M D^2) %.3g\n",
              pairs, rounded, canonical, vertex_error.value, exact_error.value);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(bad_shape, 0);
  EXPECT_LE(vertex_error.value, 1) << vertex_error.where;
  EXPECT_LE(exact_error.value, 1e-13) << exact_error.where;
  EXPECT_GT(rounded, pairs / 20);
  EXPECT_GT(canonical, pairs / 20);
}

// Mesh pairs: a fluid Kuhn box mesh of [-1/2, 1/2]^3 (n^3 cubes, n = 2 or 4; a third jittered inside), and a solid
// box mesh moved by a rigid motion: aligned (quarter turns about z and shifts by whole cells, exact: faces on
// faces, vertices on vertices; a third of those shifted again by 2^-50 of a cell along a random direction: faces
// 1e-15 apart), or turned by a random rotation; a quarter of the fluids with a hole. For every solid tetrahedron
// the search's pieces are those of brute force over all the fluid tetrahedra and, without a hole, tile it (GMP
// volume); the P1 x P1 coupling under the identity map gives 1^T B 1 = the solid's volume (with a hole and
// drop_outside, the brute-force pieces' volume); a rotated solid placed by a random affine map instead (rotation
// times shear), 1^T B 1 = the volume and 1^T B u = the exact integral of a linear u. DLMFSI_FUZZ3D_MESHES pairs (default 30), DLMFSI_FUZZ3D_SEED as
// above.
TEST(Property3d, MeshPairsTileAndCouplingKeepsTheVolume) {
  const long meshes = env_long("DLMFSI_FUZZ3D_MESHES", 30);
  std::mt19937_64 rng(static_cast<std::uint64_t>(env_long("DLMFSI_FUZZ3D_SEED", 20240601)) + 1);
  auto integer = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const double pi = std::acos(-1.0);
  const auto start = std::chrono::steady_clock::now();
  Worst tiling, coupling, mapped;
  long solid_tets = 0, pieces = 0, mismatches = 0, aligned_count = 0, nudged = 0, holes = 0;
  for (long it = 0; it < meshes; ++it) {
    const int n = integer(0, 1) ? 4 : 2;
    const double h = 1.0 / n;
    const bool jittered = integer(0, 2) == 0;
    Mesh3 fluid = test3d::box_mesh(n, n, n, {-0.5, -0.5, -0.5}, {1, 1, 1}, jittered ? 0.3 : 0,
                                   static_cast<unsigned>(rng()));
    // A quarter of the fluids get a hole (the tetrahedra whose centroid lies within 0.2 of a point near the
    // centre removed: a non-convex mesh the solid leaves and re-enters, assembled with drop_outside).
    const bool hole = integer(0, 3) == 0;
    if (hole) {
      fluid = test3d::with_hole(fluid, {uniform(-0.1, 0.1), uniform(-0.1, 0.1), uniform(-0.1, 0.1)}, 0.2);
      ++holes;
    }
    const bool aligned = integer(0, 2) != 0;
    const int m1 = integer(1, std::max(1, n / 2)), m2 = integer(1, std::max(1, n / 2)), m3 = integer(1, std::max(1, n / 2));
    Mesh3 solid;
    if (aligned) {
      ++aligned_count;
      solid = test3d::box_mesh(m1, m2, m3, {-(m1 / 2) * h, -(m2 / 2) * h, -(m3 / 2) * h}, {m1 * h, m2 * h, m3 * h});
      for (int q = integer(0, 3); q > 0; --q) solid = test3d::quarter_turn(solid, {0, 0, 0});
      const int lim = std::max(0, n / 2 - 1 - std::max({m1, m2, m3}) / 2 - 1);
      Point3 shift{h * integer(-lim, lim), h * integer(-lim, lim), h * integer(-lim, lim)};
      if (integer(0, 2) == 0) {  // faces 2^-50 of a cell apart
        ++nudged;
        shift = shift + std::ldexp(h, -50) * Point3{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      }
      solid = test3d::moved(solid, {0, 0, 1}, 0, {0, 0, 0}, shift);
    } else {
      const Point3 size{uniform(0.1, 0.4), uniform(0.1, 0.4), uniform(0.1, 0.4)};
      solid = test3d::box_mesh(m1, m2, m3, -0.5 * size, size);
      solid = test3d::moved(solid, {uniform(-1, 1), uniform(-1, 1), uniform(0.1, 1)}, uniform(0, 2 * pi), {0, 0, 0},
                            {uniform(-0.05, 0.05), uniform(-0.05, 0.05), uniform(-0.05, 0.05)});
    }
    const std::string where = "mesh pair " + std::to_string(it) + (aligned ? " (aligned)" : " (rotated)");
    FluidGrid3 grid(fluid);
    FluidSearch3 search(grid);
    int hint = 0;
    double volume = 0, covered = 0;  // the solid's volume, and (with a hole) that of its part inside the fluid
    for (int k = 0; k < solid.size(); ++k) {
      Point3 t[4];
      solid.corners(k, t);
      std::vector<std::pair<int, double>> found, brute;
      search.for_each_piece(t, hint, [&](int kf, const Piece3& p) { found.push_back({kf, p.volume()}); });
      std::sort(found.begin(), found.end());
      // the search's clipper (clip_filtered), so that the pieces compare bit for bit
      TetFaces t_faces;
      t_faces.set(t);
      for (int kf = 0; kf < fluid.size(); ++kf) {
        Point3 c[4];
        fluid.corners(kf, c);
        unsigned beyond;
        const Piece3 p = clip_filtered(t, t_faces, c, beyond);
        if (p.n > 0) brute.push_back({kf, p.volume()});
      }
      if (found != brute && ++mismatches <= 5)
        ADD_FAILURE() << where << ", solid tetrahedron " << k << ": the search's pieces are not brute force's";
      double sum = 0;
      for (const auto& piece : found) sum += piece.second;
      const double want = std::fabs(ref::exact_tet_volume(t[0], t[1], t[2], t[3]));
      for (const auto& piece : brute) covered += piece.second;
      volume += want;
      if (hole) continue;  // the pieces tile only the part inside the fluid
      tiling.update(std::fabs(sum - want) / want, where + ", solid tetrahedron " + std::to_string(k));
      ++solid_tets;
      pieces += static_cast<long>(found.size());
    }
    const double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const test3d::AffineMap3 map(solid, identity, {0, 0, 0});
    const test3d::P1Tet vf(fluid), vs(solid);
    CouplingOptions opt;
    opt.c1 = 0;
    opt.c2 = 1;
    opt.drop_outside = hole;
    const CsrMatrix b = assemble_coupling(FluidSide3(fluid, vf, {0}), SolidSide3(solid, vs, {0}), map, opt);
    const std::vector<double> one_s(solid.vertices.size(), 1), one_f(fluid.vertices.size(), 1);
    // relative to the solid's volume; with a hole against the brute-force pieces' volumes
    coupling.update(std::fabs(test3d::bilinear(b, one_s, one_f) - (hole ? covered : volume)) / volume, where);
    if (hole || aligned) continue;  // (an aligned solid may be too large to turn inside the fluid)
    // The same solid placed by an affine map X(s) = c + A (s - c) (A a rotation times a shear, det 0.85 to
    // 1.16, |A| <= 1.15: inside the fluid; c the solid's centre) instead: the coupling integrates over the reference solid, so 1^T B 1 is its
    // volume whatever the map, and for the linear fluid function u(x) = g . x + 1, 1^T B u = sum over the solid
    // tetrahedra of vol_k u(X(centroid_k)), exactly.
    double r[3][3], a[3][3];
    test3d::rotation({uniform(-1, 1), uniform(-1, 1), uniform(0.1, 1)}, uniform(0, 2 * pi), r);
    const double shear[3][3] = {{uniform(0.95, 1.05), uniform(-0.05, 0.05), uniform(-0.05, 0.05)},
                                {0, uniform(0.95, 1.05), uniform(-0.05, 0.05)},
                                {0, 0, uniform(0.95, 1.05)}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a[i][j] = r[i][0] * shear[0][j] + r[i][1] * shear[1][j] + r[i][2] * shear[2][j];
    Point3 centre{0, 0, 0};
    for (Point3 v : solid.vertices) centre = centre + (1.0 / static_cast<double>(solid.vertices.size())) * v;
    const Point3 ac{a[0][0] * centre.x + a[0][1] * centre.y + a[0][2] * centre.z,
                    a[1][0] * centre.x + a[1][1] * centre.y + a[1][2] * centre.z,
                    a[2][0] * centre.x + a[2][1] * centre.y + a[2][2] * centre.z};
    const test3d::AffineMap3 placed(solid, a, centre - ac);
    const CsrMatrix bp = assemble_coupling(FluidSide3(fluid, vf, {0}), SolidSide3(solid, vs, {0}), placed, opt);
    const Point3 g{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    std::vector<double> u(fluid.vertices.size());
    for (size_t v = 0; v < u.size(); ++v) u[v] = dot(g, fluid.vertices[v]) + 1;
    double want_u = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point3 t[4];
      solid.corners(k, t);
      const Point3 x = placed.apply(0.25 * (t[0] + t[1] + t[2] + t[3]));
      want_u += std::fabs(ref::exact_tet_volume(t[0], t[1], t[2], t[3])) * (dot(g, x) + 1);
    }
    const double scale_u = volume * (1 + std::fabs(g.x) + std::fabs(g.y) + std::fabs(g.z));
    mapped.update(std::max(std::fabs(test3d::bilinear(bp, one_s, one_f) - volume) / volume,
                           std::fabs(test3d::bilinear(bp, one_s, u) - want_u) / scale_u),
                  where + ", under an affine map");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ property3d ] %ld mesh pairs (%ld aligned, %ld of them nudged by 2^-50 h; %ld fluids with a hole), "
              "%.1f s: %ld solid tetrahedra, %ld pieces; worst relative error: tiling %.3g, 1'B1 against the volume "
              "%.3g, under an affine map %.3g\n",
              meshes, aligned_count, nudged, holes, seconds, solid_tets, pieces, tiling.value, coupling.value,
              mapped.value);
  EXPECT_EQ(mismatches, 0);
  EXPECT_LE(tiling.value, 1e-13) << tiling.where;
  EXPECT_LE(coupling.value, 1e-13) << coupling.where;
  EXPECT_LE(mapped.value, 1e-13) << mapped.where;
}
