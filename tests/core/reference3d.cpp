#include "reference3d.hpp"

#include <gmpxx.h>

#include <array>
#include <utility>
#include <vector>

namespace dlmfsi::ref {

namespace {

struct Q3 {
  mpq_class x, y, z;
};

Q3 q(Point3 p) { return {mpq_class(p.x), mpq_class(p.y), mpq_class(p.z)}; }  // exact: doubles are rationals
Q3 sub(const Q3& a, const Q3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
mpq_class det(const Q3& u, const Q3& v, const Q3& w) {
  return u.x * (v.y * w.z - v.z * w.y) + u.y * (v.z * w.x - v.x * w.z) + u.z * (v.x * w.y - v.y * w.x);
}
mpq_class volume6(const Q3& a, const Q3& b, const Q3& c, const Q3& d) { return det(sub(b, a), sub(c, a), sub(d, a)); }

// A convex polyhedron as its faces, each a polygon of exact points (any orientation is fine: the volume
// below is taken from a point inside, with absolute values).
using Polygon = std::vector<Q3>;
using Polyhedron = std::vector<Polygon>;

// Clips the polyhedron by the half-space {x : n . x <= c} (Sutherland-Hodgman on every face, and the cut
// face made of the crossing points, in order around the cut).
Polyhedron clip(const Polyhedron& in, const Q3& n, const mpq_class& c) {
  Polyhedron out;
  std::vector<std::pair<Q3, Q3>> cut_edges;  // crossing segments on the cut plane, one per face
  bool face_on_plane = false;
  auto value = [&](const Q3& p) -> mpq_class { return n.x * p.x + n.y * p.y + n.z * p.z - c; };
  for (const Polygon& face : in) {
    Polygon kept;
    std::vector<Q3> on_plane;
    const size_t m = face.size();
    for (size_t i = 0; i < m; ++i) {
      const Q3& p = face[i];
      const Q3& r = face[(i + 1) % m];
      const mpq_class vp = value(p), vr = value(r);
      if (vp <= 0) kept.push_back(p);
      if (vp == 0) on_plane.push_back(p);
      if ((vp < 0 && vr > 0) || (vp > 0 && vr < 0)) {
        const mpq_class t = vp / (vp - vr);
        const Q3 x{p.x + t * (r.x - p.x), p.y + t * (r.y - p.y), p.z + t * (r.z - p.z)};
        kept.push_back(x);
        on_plane.push_back(x);
      }
    }
    if (kept.size() >= 3) out.push_back(kept);
    if (kept.size() >= 3 && on_plane.size() == kept.size()) face_on_plane = true;
    if (on_plane.size() == 2) cut_edges.push_back({on_plane[0], on_plane[1]});
  }
  auto same = [](const Q3& a, const Q3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  // An edge on the plane between a kept face and a removed one comes from both: once.
  for (size_t e = 0; e < cut_edges.size(); ++e)
    for (size_t f = e + 1; f < cut_edges.size(); ++f)
      if ((same(cut_edges[e].first, cut_edges[f].first) && same(cut_edges[e].second, cut_edges[f].second)) ||
          (same(cut_edges[e].first, cut_edges[f].second) && same(cut_edges[e].second, cut_edges[f].first)))
        cut_edges.erase(cut_edges.begin() + static_cast<long>(f--));
  // Chain the cut segments into the cut face (unless a kept face already lies on the plane).
  if (cut_edges.size() >= 3 && !face_on_plane) {
    Polygon face{cut_edges[0].first, cut_edges[0].second};
    std::vector<bool> used(cut_edges.size(), false);
    used[0] = true;
    for (size_t step = 1; step < cut_edges.size(); ++step)
      for (size_t e = 0; e < cut_edges.size(); ++e) {
        if (used[e]) continue;
        if (same(cut_edges[e].first, face.back())) {
          face.push_back(cut_edges[e].second);
        } else if (same(cut_edges[e].second, face.back())) {
          face.push_back(cut_edges[e].first);
        } else {
          continue;
        }
        used[e] = true;
        break;
      }
    if (same(face.front(), face.back())) face.pop_back();
    if (face.size() >= 3) out.push_back(face);
  }
  return out;
}

mpq_class volume(const Polyhedron& p) {
  if (p.empty()) return 0;
  // From the mean of the first face's first vertex and any other vertex of another face: a point of the
  // closed polyhedron; the volume is the sum over faces of the fans' |volumes|.
  Q3 o = p[0][0];
  mpq_class v = 0;
  for (const Polygon& face : p)
    for (size_t i = 1; i + 1 < face.size(); ++i) v += abs(volume6(o, face[0], face[i], face[i + 1]));
  return v / 6;
}

}  // namespace

int exact_orientation3d(Point3 a, Point3 b, Point3 c, Point3 d) { return sgn(volume6(q(a), q(b), q(c), q(d))); }

double exact_orientation3d_value(Point3 a, Point3 b, Point3 c, Point3 d, int& e) {
  const mpq_class v = volume6(q(a), q(b), q(c), q(d));
  e = 0;
  if (sgn(v) == 0) return 0;
  // doubles are dyadic: the denominator is a power of two, 2^(bits - 1)
  const long den_bits = static_cast<long>(mpz_sizeinbase(v.get_den().get_mpz_t(), 2)) - 1;
  long num_exp;
  const double m = mpz_get_d_2exp(&num_exp, v.get_num().get_mpz_t());
  e = static_cast<int>(num_exp - den_bits);
  return m;
}

double exact_tet_volume(Point3 a, Point3 b, Point3 c, Point3 d) {
  const mpq_class v = volume6(q(a), q(b), q(c), q(d)) / 6;
  return v.get_d();
}

double exact_intersection_volume(const Point3 a[4], const Point3 b[4], bool* positive) {
  if (positive) *positive = false;
  Q3 qa[4], qb[4];
  for (int i = 0; i < 4; ++i) {
    qa[i] = q(a[i]);
    qb[i] = q(b[i]);
  }
  if (sgn(volume6(qa[0], qa[1], qa[2], qa[3])) == 0 || sgn(volume6(qb[0], qb[1], qb[2], qb[3])) == 0) return 0;
  Polyhedron p;
  for (int f = 0; f < 4; ++f) p.push_back({qa[(f + 1) % 4], qa[(f + 2) % 4], qa[(f + 3) % 4]});
  // The half-spaces of b: face opposite vertex i, the side of vertex i.
  for (int i = 0; i < 4 && !p.empty(); ++i) {
    const Q3& p0 = qb[(i + 1) % 4];
    const Q3 n0 = [&] {
      const Q3 u = sub(qb[(i + 2) % 4], p0), v = sub(qb[(i + 3) % 4], p0);
      return Q3{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    }();
    const mpq_class c0 = n0.x * p0.x + n0.y * p0.y + n0.z * p0.z;
    const mpq_class vi = n0.x * qb[i].x + n0.y * qb[i].y + n0.z * qb[i].z - c0;
    // keep the side of vertex i: n . x <= c when vi < 0, else -n . x <= -c
    if (vi < 0) {
      p = clip(p, n0, c0);
    } else {
      p = clip(p, Q3{-n0.x, -n0.y, -n0.z}, -c0);
    }
  }
  const mpq_class v = volume(p);
  if (positive) *positive = sgn(v) > 0;
  return v.get_d();
}

}  // namespace dlmfsi::ref
