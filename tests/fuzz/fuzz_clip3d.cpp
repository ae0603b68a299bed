// libFuzzer target for the tetrahedron clipper: `make fuzz` builds it beside fuzz_clip with
// clang++ -fsanitize=fuzzer,address,undefined and runs each for FUZZ_TIME seconds.
//
// The input's first byte picks how the rest decodes into two tetrahedra a and b:
//   0  raw doubles: 24 little-endian doubles (NaN and infinities rejected, any other bit pattern kept);
//   1  small integers on a grid (coordinates in [-8, 8] times a power of two from the input): coincident
//      vertices, shared edges and faces, coplanar faces;
//   2  b's vertices at dyadic barycentric combinations of a's vertices (weights k/8): on a's faces, edges
//      and vertices;
//   3  mode 1 or 2 with some coordinates moved by a few ulps or by a few subnormal steps (2^-1074: the
//      configuration that once gave a piece 4e-5 too large);
//   4  a small fluid Kuhn box mesh over a box and a tetrahedron, both from raw doubles (or the tetrahedron on
//      the grid's vertices and midpoints): FluidSearch3 against a brute-force scan of the mesh, the same fluid
//      tetrahedra (the pieces are the same clip's).
// Checked for every pair of positively oriented tetrahedra (a trap, so libFuzzer keeps the input):
//   - no crash, no undefined behaviour (the sanitizers), the piece's shape (test3d::piece_shape: finite
//     vertices, faces from the exact plane sets, Euler's formula, every vertex within round-off of both
//     tetrahedra and of its faces' planes: 64 eps M, and at least two subnormal steps, 2^-1073, since for
//     tetrahedra of subnormal size the constructed vertices are multiples of 2^-1074);
//   - clip_filtered (the search's clipper) against clip: the same vertex count and plane sets, a valid shape,
//     and (volumes representable) the same volume to 1e-13 M D^2;
//   - when the pair's scale M D^2 (M the largest |coordinate|, D the diameter) lies in [2^-900, 2^900], so
//     volumes are representable: vol(a ∩ b) against the exact volume in GMP rationals, vol(b ∩ a), and a
//     split of a into four tetrahedra about its centroid tiling a ∩ b, each to 1e-13 M D^2.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/clip3d.hpp"
#include "errors.hpp"
#include "mesh/fluid_search3d.hpp"
#include "fuzz_input.hpp"
#include "geometry/predicates3d.hpp"
#include "reference3d.hpp"
#include "support3d.hpp"

using namespace dlmfsi;
using dlmfsi::fuzz::Input;
using dlmfsi::test3d::Tet;

namespace {

std::string describe(const Tet& a, const Tet& b) {
  std::string s;
  char buf[96];
  for (const Tet* t : {&a, &b}) {
    s += t == &a ? "\n a =" : "\n b =";
    for (Point3 p : *t) {
      std::snprintf(buf, sizeof buf, " (%.17g, %.17g, %.17g)", p.x, p.y, p.z);
      s += buf;
    }
  }
  return s;
}

[[noreturn]] void fail(const std::string& what, const Tet& a, const Tet& b, double x = 0, double y = 0) {
  std::fprintf(stderr, "fuzz_clip3d: %s (%.17g, %.17g)%s\n", what.c_str(), x, y, describe(a, b).c_str());
  std::abort();
}

void check_pair(Tet a, Tet b) {
  if (!test3d::finite(a) || !test3d::finite(b) || !test3d::make_positive(a) || !test3d::make_positive(b)) return;
  double m, d;
  test3d::scales(a, b, m, d);
  const Piece3 p = clip(a.data(), b.data()), q = clip(b.data(), a.data());
  // round-off of a constructed vertex: relative to the coordinates, and at least two subnormal steps
  // (tetrahedra of subnormal size have no finer coordinates)
  const double shape_tol = std::max(64 * 2.2e-16 * m, 0x1p-1073);
  for (const std::string& shape : {test3d::piece_shape(p, a, b, shape_tol), test3d::piece_shape(q, b, a, shape_tol)})
    if (!shape.empty()) fail(shape, a, b);
  // the search's clipper (clip_filtered): clip's vertex count and plane sets, a valid shape, the same volume
  TetFaces a_faces;
  a_faces.set(a.data());
  unsigned beyond;
  const Piece3 f = clip_filtered(a.data(), a_faces, b.data(), beyond);
  std::vector<int> planes_f(f.planes, f.planes + f.n), planes_p(p.planes, p.planes + p.n);
  std::sort(planes_f.begin(), planes_f.end());
  std::sort(planes_p.begin(), planes_p.end());
  if (f.n != p.n || planes_f != planes_p) fail("clip_filtered's vertices or planes are not clip's", a, b, f.n, p.n);
  const std::string filtered_shape = test3d::piece_shape(f, a, b, shape_tol);
  if (!filtered_shape.empty()) fail("clip_filtered: " + filtered_shape, a, b);
  const double scale = m * d * d;
  if (!(scale >= 0x1p-900 && scale <= 0x1p900)) return;  // volumes not representable
  const double tol = 1e-13 * scale, v = p.volume();
  if (!(std::fabs(f.volume() - v) <= tol)) fail("clip_filtered's volume against clip's", a, b, f.volume(), v);
  const double exact = ref::exact_intersection_volume(a.data(), b.data());
  if (!(std::fabs(v - exact) <= tol)) fail("volume against the exact volume", a, b, v, exact);
  if (!(std::fabs(q.volume() - v) <= tol)) fail("vol(b ∩ a) != vol(a ∩ b)", a, b, q.volume(), v);
  Tet parts[4];
  if (test3d::split4(a, parts)) {
    double s = 0;
    for (const Tet& t : parts) s += clip(t.data(), b.data()).volume();
    if (!(std::fabs(s - v) <= tol)) fail("a split in four does not tile a ∩ b", a, b, s, v);
  }
}

void grid_tets(Input& in, Tet& a, Tet& b) {
  const double unit = std::ldexp(1.0, in.small(-60, 60));
  for (Tet* t : {&a, &b})
    for (Point3& p : *t) p = {unit * in.small(-8, 8), unit * in.small(-8, 8), unit * in.small(-8, 8)};
}

void on_a(Input& in, Tet& a, Tet& b) {
  grid_tets(in, a, b);
  for (Point3& p : b) {
    if (in.byte() % 4 == 0) continue;  // keep the grid vertex
    // weights w_i / 8 summing to 1 (the last takes the rest): on a face, an edge or a vertex of a when
    // some are 0
    int w[4], left = 8;
    for (int i = 0; i < 3; ++i) {
      w[i] = in.small(0, left);
      left -= w[i];
    }
    w[3] = left;
    p = {0, 0, 0};
    for (int i = 0; i < 4; ++i) p = p + (w[i] / 8.0) * a[i];
  }
}

void perturb(Input& in, Tet& a, Tet& b) {
  for (Tet* t : {&a, &b})
    for (Point3& p : *t)
      for (double* c : {&p.x, &p.y, &p.z}) {
        const int k = in.byte();
        if (k % 5 == 0) *c = std::nextafter(*c, k & 8 ? HUGE_VAL : -HUGE_VAL);
        if (k % 7 == 0) *c += (k & 16 ? 1 : -1) * std::ldexp(static_cast<double>(k % 3 + 1), -1074);
      }
}

void check_search(Input& in) {
  double box[6];
  for (double& v : box)
    if (!in.raw(v)) return;
  const int n = in.small(1, 3), m = in.small(1, 3), l = in.small(1, 3);
  Mesh3 fluid;
  try {
    fluid = test3d::box_mesh(n, m, l, {box[0], box[1], box[2]}, {box[3], box[4], box[5]});
  } catch (const Error&) {  // non-finite vertices, flat tetrahedra
    return;
  }
  Tet t;
  if (in.byte() % 2) {
    for (Point3& p : t)
      if (!in.raw(p.x) || !in.raw(p.y) || !in.raw(p.z)) return;
  } else {  // on the grid: mesh vertices, and midpoints of two of them
    const int nv = static_cast<int>(fluid.vertices.size());
    for (Point3& p : t) {
      const Point3 u = fluid.vertices[in.byte() % nv], v = fluid.vertices[in.byte() % nv];
      p = in.byte() % 2 ? u : 0.5 * (u + v);
    }
  }
  if (!test3d::finite(t) || !test3d::make_positive(t)) return;
  FluidGrid3 grid(fluid);
  FluidSearch3 search(grid);
  int hint = 0;
  std::vector<int> found, brute;
  search.for_each_piece(t.data(), hint, [&](int k, const Piece3&) { found.push_back(k); });
  std::sort(found.begin(), found.end());
  for (int k = 0; k < fluid.size(); ++k) {
    Point3 c[4];
    fluid.corners(k, c);
    if (clip(t.data(), c).n > 0) brute.push_back(k);
  }
  if (found != brute)
    fail("FluidSearch3 and brute force find other tetrahedra", t, t, static_cast<double>(found.size()),
         static_cast<double>(brute.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Input in(data, size);
  Tet a, b;
  const int mode = in.byte() % 5;
  if (mode == 4) {
    check_search(in);
    return 0;
  }
  switch (mode) {
    case 0:
      for (Tet* t : {&a, &b})
        for (Point3& p : *t)
          if (!in.raw(p.x) || !in.raw(p.y) || !in.raw(p.z)) return 0;
      break;
    case 1:
      grid_tets(in, a, b);
      break;
    case 2:
      on_a(in, a, b);
      break;
    default:
      if (in.byte() % 2) grid_tets(in, a, b);
      else on_a(in, a, b);
      perturb(in, a, b);
  }
  check_pair(a, b);
  return 0;
}
