// The piece shared by two tetrahedra: a convex polyhedron of at most 12 vertices and 8 faces.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#include "point3.hpp"
#include "geometry/exact_sign.hpp"
#include "geometry/predicates3d.hpp"

namespace dlmfsi {

struct Piece3 {
  static constexpr int kMaxVertices = 16, kMaxFaces = 8, kMaxFaceIndices = 64;
  // v[0 .. n): the vertices. A member of an anonymous union, which the constructor leaves uninitialized (a
  // Point3 is zero-initialized: a Piece3 made for every pair clipped would clear 384 bytes).
  union {
    Point3 v[kMaxVertices];
  };
  Piece3() {}
  int n = 0;  // number of vertices; 0 when the interiors do not meet
  // Face f is the cycle of vertex indices face_index[face_start[f] .. face_start[f + 1]), in order around
  // the face (either direction). Vertex 0 is the lexicographically smallest vertex.
  unsigned char face_index[kMaxFaceIndices];
  int face_start[kMaxFaces + 1] = {0};
  int faces = 0;
  // The same faces as vertex sets: bit k of face_vertices[f] when vertex k is on face f (f < faces).
  unsigned face_vertices[kMaxFaces];
  // Which planes each vertex lies on: bits 0-3 the faces of the first tetrahedron (face i opposite its
  // vertex i), bits 4-7 those of the second (a plane shared by both keeps the first one's bit only).
  unsigned char planes[kMaxVertices];
  // True when every face was ordered from the exact plane incidences (always so for finite input: the
  // floating-point ordering that replaces it otherwise is a guard, counted by the tests).
  bool exact = true;

  // The pulling triangulation from the apex (apex()): f(apex, p, q, r) for each triangle (p, q, r) of the
  // fans of the faces that do not contain the apex. The tetrahedra tile the piece; they are not oriented.
  template <class F>
  void for_each_tetrahedron(F&& f) const {
    for_each_tetrahedron_index([&](int i, int j, int k, int l) { f(v[i], v[j], v[k], v[l]); });
  }
  // The same tetrahedra as vertex indices (the first is always the apex).
  template <class F>
  void for_each_tetrahedron_index(F&& f) const {
    for_each_tetrahedron_from(apex(), f);
  }
  // The pulling triangulation from vertex a, as vertex indices (a caller that has apex() already).
  template <class F>
  void for_each_tetrahedron_from(int a, F&& f) const {
    for (int k = 0; k < faces; ++k) {
      if (face_vertices[k] >> a & 1u) continue;
      const int s = face_start[k], e = face_start[k + 1];
      for (int i = s + 1; i + 1 < e; ++i) f(a, face_index[s], face_index[i], face_index[i + 1]);
    }
  }
  // The vertex whose pulling triangulation has the fewest tetrahedra: sum over the faces f without it of
  // (|f| - 2), i.e. 2 n - 4 (Euler) less sum over the faces f with it of (|f| - 2), maximized; the first such
  // vertex.
  int apex() const {
    int score[kMaxVertices] = {0};
    for (int k = 0; k < faces; ++k) {
      const int s = face_start[k], e = face_start[k + 1];
      for (int i = s; i < e; ++i) score[face_index[i]] += e - s - 2;
    }
    int best = 0;
    for (int i = 1; i < n; ++i) best = score[i] > score[best] ? i : best;
    return best;
  }
  // Sum of the pulling triangulation's |volumes| (each tetrahedron's is >= 0 exactly; round-off only).
  double volume() const {
    double s = 0;
    for_each_tetrahedron([&s](Point3 o, Point3 p, Point3 q, Point3 r) { s += std::fabs(volume6(o, p, q, r)); });
    return s / 6;
  }
};

// The four face planes of a positively oriented tetrahedron t, each oriented so that side(j, x) > 0 on t's
// side of face j (opposite t[j]): side(j, x) = orient3d of t with t[j] replaced by x, exactly. Formed once
// for a tetrahedron clipped against many others.
struct TetFaces {
  PlaneSide face[4];
  void set(const Point3 t[4]) {
    // orient3d(t with t[j] <- x) = (-1)^(3 - j) orient3d(t_k, t_l, t_m, x) for the others k < l < m
    face[0].set(t[1], t[3], t[2]);
    face[1].set(t[0], t[2], t[3]);
    face[2].set(t[0], t[3], t[1]);
    face[3].set(t[0], t[1], t[2]);
  }
  int side(int j, Point3 x) const { return face[j].sign(x); }
};

// The normals of TetFaces' planes without their points (face j's plane passes through t[j == 0 ? 1 : 0]):
// n(j), pn(j) are face[j].n, face[j].pn bit for bit. They depend on differences of t's vertices only, so an
// exact translation of t (translate_exactly) keeps them. Kept for each tetrahedron of a mesh clipped many
// times (24 doubles a tetrahedron), where forming TetFaces for every pair would repeat them. Plain doubles:
// an array of them is not cleared when it is made.
//
// exact[j] = k + 1: face j's plane is axis-aligned, x_k = c (its three points share coordinate k exactly), and its
// normal's one nonzero component has a certain sign (beyond orient2d's error bound, 4 eps times the minors'
// absolute sum); else 0. Then the side of a point x is exactly sign(x_k - c) sign(n_k), zero exactly where x_k == c
// (the difference of two doubles is 0 only when they are equal), and the estimate (x - p) . n = fl(x_k - c) n_k
// has that sign unless it underflows: box and extruded fluid meshes, whose solid vertices often lie on their
// planes, get those sides without the exact clip.
struct TetNormals {
  double normal[4][3], permanent[4][3];
  unsigned char exact[4];
  Point3 n(int j) const { return {normal[j][0], normal[j][1], normal[j][2]}; }
  Point3 pn(int j) const { return {permanent[j][0], permanent[j][1], permanent[j][2]}; }
  void set(const Point3 t[4]) {
    TetFaces faces;
    faces.set(t);
    for (int j = 0; j < 4; ++j) {
      const PlaneSide& f = faces.face[j];
      normal[j][0] = f.n.x;
      normal[j][1] = f.n.y;
      normal[j][2] = f.n.z;
      permanent[j][0] = f.pn.x;
      permanent[j][1] = f.pn.y;
      permanent[j][2] = f.pn.z;
      const int k = f.p.x == f.q.x && f.p.x == f.r.x ? 0 : f.p.y == f.q.y && f.p.y == f.r.y ? 1
                    : f.p.z == f.q.z && f.p.z == f.r.z ? 2 : -1;
      // (the bound holds where the minors do not underflow: their absolute sum at least 2^-1000)
      const bool certain = k >= 0 && permanent[j][k] >= 0x1p-1000 &&
                           std::fabs(normal[j][k]) > 0x1p-51 * permanent[j][k] && normal[j][(k + 1) % 3] == 0 &&
                           normal[j][(k + 2) % 3] == 0;
      exact[j] = static_cast<unsigned char>(certain ? k + 1 : 0);
    }
  }
};

// Values clip finds for one tetrahedron a clipped against many tetrahedra b (a mapped solid tetrahedron and
// the fluid tetrahedra it meets): crossings that involve points of b, each a function of its arguments alone
// (crossing() orders them itself), and orientation signs that the floating-point filter left to the exact
// evaluation, kept under a key of a's part (a tag) and b's points as bits. A neighbour of b that shares those
// points (a vertex, an edge: 4 to 6 fluid tetrahedra around it; a face: 2) gets the same value back, bit for
// bit, instead of computing it again. Direct-mapped: a key whose slot is taken replaces the
// entry there. Valid while a stays the same: clear() whenever a changes.
class ClipMemo3 {
 public:
  static constexpr int kSlots = 128, kMaxKeyPoints = 3;
  void clear() { used_[0] = used_[1] = 0; }
  // The value (a point, or a sign as its x) kept for (tag, the m points p, m <= kMaxKeyPoints) if any: true and out set; else false, and
  // slot, hash say where store() puts it.
  bool find(int tag, const Point3* p, int m, Point3& out, int& slot, std::uint64_t& hash) const {
    std::uint64_t h = static_cast<std::uint64_t>(tag);
    for (int i = 0; i < m; ++i) h = rotate(h, 29) ^ (bits(p[i].x) + rotate(bits(p[i].y), 21) + rotate(bits(p[i].z), 42));
    h *= 0x9E3779B97F4A7C15ull;
    hash = h;
    slot = static_cast<int>(h >> 57);  // the top 7 bits: kSlots = 128
    if (!(used_[slot >> 6] >> (slot & 63) & 1u)) return false;
    const Slot& e = slots_[slot];
    if (e.hash != hash || e.tag != tag) return false;
    for (int i = 0; i < m; ++i)
      if (bits(e.key[3 * i]) != bits(p[i].x) || bits(e.key[3 * i + 1]) != bits(p[i].y) ||
          bits(e.key[3 * i + 2]) != bits(p[i].z))
        return false;
    out = {e.value[0], e.value[1], e.value[2]};
    return true;
  }
  void store(int slot, std::uint64_t hash, int tag, const Point3* p, int m, Point3 value) {
    Slot& e = slots_[slot];
    e.hash = hash;
    e.tag = tag;
    for (int i = 0; i < m; ++i) {
      e.key[3 * i] = p[i].x;
      e.key[3 * i + 1] = p[i].y;
      e.key[3 * i + 2] = p[i].z;
    }
    e.value[0] = value.x;
    e.value[1] = value.y;
    e.value[2] = value.z;
    used_[slot >> 6] |= std::uint64_t{1} << (slot & 63);
  }

 private:
  static std::uint64_t rotate(std::uint64_t v, int r) { return v << r | v >> (64 - r); }
  static std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  }
  // Plain doubles (a Point3 is zero-initialized): a memo made for each solid tetrahedron costs nothing
  // until it is used.
  struct Slot {
    std::uint64_t hash;
    int tag;
    double key[3 * kMaxKeyPoints], value[3];
  };
  Slot slots_[kSlots];
  std::uint64_t used_[2] = {0, 0};
};

// Intersection of the closed, positively oriented tetrahedra a and b (orient3d(t[0], t[1], t[2], t[3]) > 0).
//
// Every decision is an exact orient3d sign on the input coordinates (predicates3d.hpp):
//  - the interiors meet iff no face plane of a or b has the other tetrahedron on its closed outer side and
//    at least 4 of the candidate vertices below exist (when no face plane separates them, tetrahedra whose
//    interiors do not meet share at most a segment, 2 vertices);
//  - the vertices are: the vertices of a in closed b; those of b in closed a (one copy of a vertex shared by
//    both); the crossings of an edge of one with the open face of the other (edge endpoints strictly on
//    either side of the face's plane, the edge's line strictly inside the face's three edges); the proper
//    crossings of an edge of a with a coplanar edge of b. Each is a vertex of the piece, found once, and
//    with it the set of face planes it lies on (from the signs);
//  - two vertices of a face are neighbours around it iff they share another plane (the line where the two
//    planes meet holds one edge of the piece), so each face's cycle follows from the plane sets alone;
//  - a crossing point is computed from its segment and plane (or its two segments) in a canonical order
//    (each point set sorted lexicographically), so every tetrahedron having that edge and that face (or
//    those edges) gets bit-identical coordinates: neighbouring tetrahedra sharing a face agree.
// Degenerate cases handled by name: shared face (either orientation), shared edge, shared vertex, vertex on
// a face, vertex on an edge, edge through an edge, coplanar faces overlapping, one tetrahedron inside the
// other, identical tetrahedra. Nothing is dropped: there is no size threshold.
Piece3 clip(const Point3 a[4], const Point3 b[4]);

// The same, also telling across which faces of b the tetrahedron a reaches: bit j of beyond is set when a
// vertex of a lies strictly outside the plane of b's face j (opposite b[j]). Only there can a's interior
// meet a tetrahedron on the other side of that face. Set whenever the piece is not empty. When a lies in
// closed b (beyond == 0) the piece is a itself, and when b lies in closed a it is b.
Piece3 clip(const Point3 a[4], const Point3 b[4], unsigned& beyond);

// The same with a's face planes formed by the caller (a = the mapped solid tetrahedron, clipped against
// every fluid tetrahedron it meets) and, when memo is given, the crossings kept for a (the same piece bit
// for bit as without it).
Piece3 clip(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], unsigned& beyond,
            ClipMemo3* memo = nullptr);

// The same piece (and beyond), found first in floating point: a cut by b's face planes one after another,
// a simple polytope whose vertices keep their three neighbours, each vertex's side of each plane taken
// from its orient3d value and a bound on that value's error (the filter's for a's vertices; for a crossing,
// interpolated from its edge's ends with their bounds carried). When every side is certified (no value
// within its bound: no vertex on or within round-off of a plane), the piece's vertices, their plane sets
// and its faces are those of the exact piece, and its crossings are rounded, within 2^-40 of their edge's
// length along it, but not canonical (a neighbour sharing the face may get them a few ulps apart; b's
// vertices are exact). Otherwise, and for a in b, it is clip()'s piece: coincident and touching tetrahedra
// (shared faces, edges, vertices) are decided exactly as there.
Piece3 clip_filtered(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], unsigned& beyond,
                     ClipMemo3* memo = nullptr);
// The same with b's plane normals given (b_normals.set(b), or of b before an exact translation).
Piece3 clip_filtered(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], const TetNormals& b_normals,
                     unsigned& beyond, ClipMemo3* memo = nullptr);

// out = t - o for the n points of t when every coordinate's subtraction is exact (its TwoSum error term is
// zero); false otherwise. An exact translation changes no orient3d sign and no lexicographic order, so clip
// decides everything on translated tetrahedra as on the originals; only the crossings, constructed from the
// translated coordinates, are rounded to the ulp of the local coordinates rather than of |t|.
inline bool translate_exactly(const Point3* t, int n, Point3 o, Point3* out) {
  bool exact = true;
  for (int i = 0; i < n; ++i) {
    exact = exact_difference(t[i].x, o.x, out[i].x) && exact;
    exact = exact_difference(t[i].y, o.y, out[i].y) && exact;
    exact = exact_difference(t[i].z, o.z, out[i].z) && exact;
  }
  return exact;
}

// The point where segment [p, q] crosses the plane through x, y, z (it must cross it), canonical in the
// order of p, q and of x, y, z.
Point3 crossing(Point3 p, Point3 q, Point3 x, Point3 y, Point3 z);

// The point where the coplanar segments [p, q] and [r, s] cross (properly), canonical in the order of the
// four arguments and of the two segments.
Point3 crossing(Point3 p, Point3 q, Point3 r, Point3 s);

}  // namespace dlmfsi
