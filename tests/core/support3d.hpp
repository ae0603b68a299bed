// Test helpers for the 3D core: tetrahedra, their splits, and the checks of a piece's shape.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "clip3d.hpp"
#include "predicates3d.hpp"
#include "reference3d.hpp"

namespace dlmfsi::test3d {

using Tet = std::array<Point3, 4>;

inline double tet_volume(const Tet& t) { return volume6(t[0], t[1], t[2], t[3]) / 6; }

// Orders t positively; false when it is flat (exactly).
inline bool make_positive(Tet& t) {
  const int o = orient3d(t[0], t[1], t[2], t[3]);
  if (o == 0) return false;
  if (o < 0) std::swap(t[2], t[3]);
  return true;
}

inline bool finite(const Tet& t) {
  for (Point3 p : t)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

// The largest |coordinate| and the diameter of the bounding box of two tetrahedra: the round-off floor
// of a constructed vertex is about eps * M, that of a volume eps * M * D^2.
inline void scales(const Tet& a, const Tet& b, double& m, double& d) {
  Point3 lo = a[0], hi = a[0];
  m = 0;
  for (const Tet* t : {&a, &b})
    for (Point3 p : *t) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    }
  d = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

// Splits t into four tetrahedra about its centroid, t_k = t with vertex k replaced by the centroid
// (positively oriented, sharing faces pairwise); false when the rounded centroid is not strictly inside.
inline bool split4(const Tet& t, Tet out[4]) {
  const Point3 c = 0.25 * (t[0] + t[1] + t[2] + t[3]);
  for (int k = 0; k < 4; ++k) {
    out[k] = t;
    out[k][k] = c;
    if (orient3d(out[k][0], out[k][1], out[k][2], out[k][3]) <= 0) return false;
  }
  return true;
}

// The shape of a piece of a and b: empty or at least 4 finite vertices; faces ordered from the exact plane
// sets; Euler's V - E + F = 2; every vertex within tol of the closed a and b, and of its faces' planes.
// Returns an empty string when it holds, else what failed.
inline std::string piece_shape(const Piece3& p, const Tet& a, const Tet& b, double tol) {
  if (p.n == 0) return "";
  if (p.n < 4) return "fewer than 4 vertices";
  if (!p.exact) return "a face ordered by the floating-point guard";
  for (int k = 0; k < p.n; ++k)
    if (!std::isfinite(p.v[k].x) || !std::isfinite(p.v[k].y) || !std::isfinite(p.v[k].z)) return "non-finite vertex";
  int sum = 0;
  for (int f = 0; f < p.faces; ++f) sum += p.face_start[f + 1] - p.face_start[f];
  if (sum % 2 || p.n - sum / 2 + p.faces != 2) return "Euler characteristic is not 2";
  // Signed distance to a face's plane, >= 0 inside, computed on coordinates scaled by a power of two
  // near 1 / max |coordinate| (exact), so that nothing underflows or overflows at 1e-100 or 1e100.
  double m = 0;
  for (const Tet* t : {&a, &b})
    for (Point3 p : *t) m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  int e;
  std::frexp(m, &e);
  auto down = [e](Point3 p) { return Point3{std::ldexp(p.x, -e), std::ldexp(p.y, -e), std::ldexp(p.z, -e)}; };
  auto distance = [&](const Tet& t, int face, Point3 v) {
    Point3 u[4] = {down(t[0]), down(t[1]), down(t[2]), down(t[3])};
    const Point3 q = u[(face + 1) % 4], r = u[(face + 2) % 4], s = u[(face + 3) % 4];
    // the exact volume over the area: thin faces of slivers have normals far too inexact for n . (v - q)
    Point3 n = cross(r - q, s - q);
    const double len = std::sqrt(dot(n, n));
    const double d = 6 * ref::exact_tet_volume(q, r, s, down(v)) / len;
    return std::ldexp(ref::exact_orientation3d(q, r, s, u[face]) > 0 ? d : -d, e);
  };
  for (int k = 0; k < p.n; ++k)
    for (int f = 0; f < 4; ++f) {
      if (distance(a, f, p.v[k]) < -tol) return "vertex outside a";
      if (distance(b, f, p.v[k]) < -tol) return "vertex outside b";
      if ((p.planes[k] >> f & 1) && std::fabs(distance(a, f, p.v[k])) > tol) return "vertex off its plane of a";
      if ((p.planes[k] >> (4 + f) & 1) && std::fabs(distance(b, f, p.v[k])) > tol) return "vertex off its plane of b";
    }
  return "";
}

}  // namespace dlmfsi::test3d
