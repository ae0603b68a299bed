// libFuzzer target for the clipper (and the fluid search): `make fuzz` builds it with
// clang++ -fsanitize=fuzzer,address,undefined and runs it for FUZZ_TIME seconds.
//
// The input's first byte picks how the rest decodes into two triangles a and b:
//   0  raw doubles: 12 little-endian doubles (NaN and infinities rejected, any other bit pattern kept);
//   1  small integers on a grid (coordinates in [-8, 8] times a power of two from the input): coincident
//      vertices, shared and collinear edges;
//   2  b's vertices on a's edge lines at dyadic parameters k/8, or on a's vertices: vertex on edge,
//      vertex on vertex, collinear overlapping edges;
//   3  mode 1 or 2 with some coordinates moved by a few ulps (perturbed coincidences);
//   4  a small fluid grid mesh over a box and a triangle, both from raw doubles: FluidSearch against a
//      brute-force scan of the mesh (the same pieces; where areas are representable, the same total to
//      1e-13 of the sum of their |areas|).
// Checked for every pair (a trap, so libFuzzer keeps the input):
//   - no crash, no undefined behaviour (the sanitizers), no NaN or infinite vertex, 0 or 3..6 vertices;
//   - when the pair's scale M D (M the largest |coordinate|, D the diameter) lies in [2^-900, 2^900], so
//     areas are representable: area(clip(a, b)) <= min(area a, area b) + tol and >= -tol,
//     area(clip(a, b)) == area(clip(b, a)) to tol, the pieces convex and counter-clockwise (up to the
//     rounding of constructed vertices), and a split of a into three triangles about an interior point
//     tiles clip(a, b); tol = 1e-13 M D.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "geometry/clip.hpp"
#include "errors.hpp"
#include "mesh/fluid_search.hpp"
#include "fuzz_input.hpp"
#include "mesh/mesh.hpp"
#include "piece_check.hpp"
#include "geometry/predicates.hpp"

using namespace dlmfsi;
using dlmfsi::fuzz::Input;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

[[noreturn]] void fail(const char* what, const Point a[3], const Point b[3], double x = 0, double y = 0) {
  std::fprintf(stderr, "fuzz_clip: %s (%.17g, %.17g)\n a = (%.17g, %.17g) (%.17g, %.17g) (%.17g, %.17g)\n b = (%.17g, %.17g) (%.17g, %.17g) (%.17g, %.17g)\n",
               what, x, y, a[0].x, a[0].y, a[1].x, a[1].y, a[2].x, a[2].y, b[0].x, b[0].y, b[1].x, b[1].y, b[2].x, b[2].y);
  std::abort();
}

bool ccw(Point t[3]) {
  const int o = orient2d(t[0], t[1], t[2]);
  if (o == 0) return false;
  if (o < 0) std::swap(t[1], t[2]);
  return true;
}

void check_structure(const Piece& p, const Point a[3], const Point b[3]) {
  if (p.n != 0 && (p.n < 3 || p.n > Piece::kMaxVertices)) fail("bad vertex count", a, b, p.n);
  for (int i = 0; i < p.n; ++i)
    if (!std::isfinite(p.v[i].x) || !std::isfinite(p.v[i].y)) fail("non-finite vertex", a, b, p.v[i].x, p.v[i].y);
}

void check_pair(Point a[3], Point b[3]) {
  if (!ccw(a) || !ccw(b)) return;
  const Piece pab = clip(a, b), pba = clip(b, a);
  check_structure(pab, a, b);
  check_structure(pba, b, a);
  if ((pab.n == 0) != (pba.n == 0)) fail("empty one way only", a, b, pab.n, pba.n);
  const double M = ref::max_abs_coordinate(a, b), D = ref::box_diameter(a, b);
  const double scale = M * D;
  if (!(scale >= 0x1p-900 && scale <= 0x1p+900)) return;  // areas not representable: structure only
  const double tol = 1e-13 * scale;
  const double A = pab.area(), B = pba.area();
  if (!std::isfinite(A) || !std::isfinite(B)) fail("non-finite area", a, b, A, B);
  const double area_a = 0.5 * area2(a[0], a[1], a[2]), area_b = 0.5 * area2(b[0], b[1], b[2]);
  if (A > std::min(area_a, area_b) + tol) fail("piece larger than a triangle", a, b, A, std::min(area_a, area_b));
  if (A < -tol) fail("negative area", a, b, A);
  if (std::fabs(A - B) > tol) fail("area(clip(a, b)) != area(clip(b, a))", a, b, A, B);
  for (const Piece* p : {&pab, &pba}) {
    const ref::PieceCheck c = ref::check_piece(*p, M, 8 * kEps);
    if (!c.error.empty()) {
      std::fprintf(stderr, "fuzz_clip: %s\n", c.error.c_str());
      fail("piece not convex counter-clockwise", a, b);
    }
  }
  // Tiling: a split about an interior point (three triangles sharing edges) tiles clip(a, b).
  const Point c{(a[0].x + a[1].x + a[2].x) / 3, (a[0].y + a[1].y + a[2].y) / 3};
  if (!std::isfinite(c.x) || !std::isfinite(c.y)) return;
  for (int i = 0; i < 3; ++i)
    if (orient2d(a[i], a[(i + 1) % 3], c) <= 0) return;
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const Point s[3] = {a[i], a[(i + 1) % 3], c};
    const Piece p = clip(s, b);
    check_structure(p, s, b);
    sum += p.area();
  }
  if (std::fabs(sum - A) > tol) fail("the pieces of a split triangle do not add up", a, b, sum, A);
}

// Mode 4: pieces of a triangle over a small grid mesh, FluidSearch against brute force.
void check_mesh(Input& in) {
  double x0, y0, w, h;
  if (!in.raw(x0) || !in.raw(y0) || !in.raw(w) || !in.raw(h)) return;
  const int n = in.small(1, 4), m = in.small(1, 4);
  Point t[3];
  for (auto& p : t)
    if (!in.raw(p.x) || !in.raw(p.y)) return;
  if (!ccw(t)) return;
  Mesh fluid;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) fluid.vertices.push_back({x0 + w * i / n, y0 + h * j / m});
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      fluid.triangles.push_back({v, v + 1, v + n + 2});
      fluid.triangles.push_back({v, v + n + 2, v + n + 1});
    }
  try {
    fluid.build_adjacency();  // throws for non-finite vertices and flat or clockwise triangles
  } catch (const Error&) {
    return;
  }
  FluidGrid grid(fluid);
  FluidSearch search(grid);
  int hint = 0, found = 0, brute = 0;
  double sum = 0, brute_sum = 0, brute_abs = 0;
  search.for_each_piece(t, hint, [&](int, const Piece& p) {
    check_structure(p, t, t);
    ++found;
    sum += p.area();
  });
  for (int k = 0; k < fluid.size(); ++k) {
    Point f[3];
    fluid.corners(k, f);
    const Piece p = clip(t, f);
    if (p.n > 0) {
      ++brute;
      brute_sum += p.area();
      brute_abs += std::fabs(p.area());
    }
  }
  if (found != brute) fail("FluidSearch and brute force find different pieces", t, t, found, brute);
  // The same pieces summed in another order agree to the rounding of the sums (relative to the sum of the
  // |areas|), where areas are representable: the pair checks' scale M D, over the triangle and the box
  // (beyond it the constructions overflow and the areas are meaningless).
  double lo_x = std::min(x0, x0 + w), hi_x = std::max(x0, x0 + w), lo_y = std::min(y0, y0 + h), hi_y = std::max(y0, y0 + h);
  for (const Point& p : t) {
    lo_x = std::min(lo_x, p.x);
    hi_x = std::max(hi_x, p.x);
    lo_y = std::min(lo_y, p.y);
    hi_y = std::max(hi_y, p.y);
  }
  const double M = std::max({std::fabs(lo_x), std::fabs(hi_x), std::fabs(lo_y), std::fabs(hi_y)});
  const double scale = M * std::max(hi_x - lo_x, hi_y - lo_y);
  if (!(scale >= 0x1p-900 && scale <= 0x1p+900)) return;
  if (std::isfinite(brute_abs) && std::fabs(sum - brute_sum) > 1e-13 * brute_abs)
    fail("FluidSearch and brute force add up differently", t, t, sum, brute_sum);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Input in(data, size);
  const int mode = in.byte() % 5;
  Point a[3], b[3];
  if (mode == 0) {
    for (Point* t : {a, b})
      for (int i = 0; i < 3; ++i)
        if (!in.raw(t[i].x) || !in.raw(t[i].y)) return 0;
  } else if (mode == 4) {
    check_mesh(in);
    return 0;
  } else {
    const int base = mode == 3 ? 1 + in.byte() % 2 : mode;
    const double s = std::ldexp(1.0, in.small(-60, 60) * 17);  // 2^-1020 .. 2^1020
    if (base == 1) {
      for (Point* t : {a, b})
        for (int i = 0; i < 3; ++i) t[i] = {s * in.small(-8, 8), s * in.small(-8, 8)};
    } else {
      for (int i = 0; i < 3; ++i) a[i] = {s * in.small(-8, 8), s * in.small(-8, 8)};
      for (int j = 0; j < 3; ++j) {
        const int kind = in.small(0, 3);
        if (kind <= 1) {
          const int i = in.small(0, 2);
          const double t = in.small(-8, 16) / 8.0;
          const Point d = a[(i + 1) % 3] - a[i];
          b[j] = {a[i].x + t * d.x, a[i].y + t * d.y};
        } else if (kind == 2) {
          b[j] = a[in.small(0, 2)];
        } else {
          b[j] = {s * in.small(-8, 8), s * in.small(-8, 8)};
        }
      }
      if (in.byte() % 2) std::swap(a, b);
    }
    if (mode == 3) {
      const int count = in.small(1, 4);
      for (int k = 0; k < count; ++k) {
        Point* t = in.byte() % 2 ? a : b;
        const int i = in.small(0, 2);
        double& v = in.byte() % 2 ? t[i].x : t[i].y;
        const int ulps = in.small(-3, 3);
        for (int u = 0; u < std::abs(ulps); ++u) v = std::nextafter(v, ulps > 0 ? HUGE_VAL : -HUGE_VAL);
        if (!std::isfinite(v)) return 0;
      }
    }
    for (Point* t : {a, b})
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(t[i].x) || !std::isfinite(t[i].y)) return 0;
  }
  check_pair(a, b);
  return 0;
}
