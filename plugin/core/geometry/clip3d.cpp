#include "geometry/clip3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "geometry/predicates3d.hpp"

namespace dlmfsi {

namespace {

// Edges of a tetrahedron by vertex pair (k < l), and the index of edge (k, l).
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kEdgeIndex[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
// Face i of a tetrahedron (opposite vertex i): its vertices in increasing order.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

// The planes (bits) of a tetrahedron's faces that contain its vertex i, or its edge (k, l).
inline unsigned faces_at_vertex(int i) { return 0xFu & ~(1u << i); }
inline unsigned faces_at_edge(int k, int l) { return 0xFu & ~(1u << k) & ~(1u << l); }

// kStraddling.pairs[pos][neg]: the edges e whose ends lie strictly on either side of a plane, as bits 4 e (the
// layout of crossing_pairs below), from the masks of the vertices strictly on its positive and negative side.
constexpr unsigned straddling(unsigned pos, unsigned neg) {
  unsigned edges = 0;
  for (int e = 0; e < 6; ++e) {
    const unsigned k = 1u << kEdge[e][0], l = 1u << kEdge[e][1];
    if (((pos & k) && (neg & l)) || ((pos & l) && (neg & k))) edges |= 1u << (4 * e);
  }
  return edges;
}
struct StraddlingTable {
  unsigned pairs[16][16];
  constexpr StraddlingTable() : pairs() {
    for (unsigned pos = 0; pos < 16; ++pos)
      for (unsigned neg = 0; neg < 16; ++neg) pairs[pos][neg] = straddling(pos, neg);
  }
};
constexpr StraddlingTable kStraddling;

// The pairs (edge e of one tetrahedron, face plane j of the other) where the edge crosses the plane strictly,
// as bits 4 e + j (so that visiting the set bits upwards goes edge by edge, plane by plane), from the
// vertices' sides: pos[j] and neg[j] the masks of the vertices strictly on the positive and negative side of
// plane j.
inline unsigned crossing_pairs(const unsigned pos[4], const unsigned neg[4]) {
  unsigned pairs = 0;
  for (int j = 0; j < 4; ++j) pairs |= kStraddling.pairs[pos[j]][neg[j]] << j;
  return pairs;
}

// kPermutationSign[c][o]: the sign of the permutation (c, o, u, v) of (0, 1, 2, 3), u < v the other two.
constexpr int kPermutationSign[4][4] = {{0, 1, -1, 1}, {-1, 0, 1, -1}, {1, -1, 0, 1}, {-1, 1, -1, 0}};

// Where an edge (s, e) of one tetrahedron t' crosses the plane of face `cut` of a positively oriented
// tetrahedron t strictly, the sign of the crossing X with respect to the plane of another face `other` of t
// (the side functions f: f_j(t[j]) = det t > 0). The ends' signs side_s, side_e decide it unless they are
// strictly opposite (X lies strictly between s and e). Otherwise, with (u, v), u < v, the edge of t where the
// two planes meet,
//   f_other(X) (f_cut(s) - f_cut(e)) = f_cut(s) f_other(e) - f_cut(e) f_other(s) = kappa orient3d(s, e, t_u, t_v)
// (both sides affine in s and in e, antisymmetric, zero where the line s e meets the edge's line), and
// s = t[cut], e = t[other] give det(t)^2 > 0 on the left, so kappa has the sign of the permutation
// (cut, other, u, v); f_cut(s) - f_cut(e) has the sign of cut_side_s. orient() gives the orientation's
// sign, asked only then.
template <class Orient>
inline int crossing_side(int side_s, int side_e, int cut_side_s, int permutation_sign, Orient&& orient) {
  if (side_s >= 0 && side_e >= 0) return side_s > 0 || side_e > 0 ? 1 : 0;
  if (side_s <= 0 && side_e <= 0) return -1;
  return permutation_sign * orient() * cut_side_s;
}

// lex_less(a, b) with every comparison made (no short-circuit: the outcome is data, not predictable).
inline bool lex_less_flat(Point3 a, Point3 b) {
  return (a.x < b.x) | ((a.x == b.x) & ((a.y < b.y) | ((a.y == b.y) & (a.z < b.z))));
}

// p, q in lexicographic order, by selects rather than a branch.
inline void sort2(Point3& p, Point3& q) {
  const bool swap = lex_less_flat(q, p);
  const Point3 lo{swap ? q.x : p.x, swap ? q.y : p.y, swap ? q.z : p.z};
  const Point3 hi{swap ? p.x : q.x, swap ? p.y : q.y, swap ? p.z : q.z};
  p = lo;
  q = hi;
}

inline void sort3(Point3& x, Point3& y, Point3& z) {
  sort2(x, y);
  sort2(y, z);
  sort2(x, y);
}

// Clamps p to the box of the points given (where the constructed point is known to lie).
inline Point3 clamp_to(Point3 p, Point3 lo, Point3 hi) {
  return {std::min(hi.x, std::max(lo.x, p.x)), std::min(hi.y, std::max(lo.y, p.y)), std::min(hi.z, std::max(lo.z, p.z))};
}

// The intersection of the boxes of two point sets, [lo, hi]: each set's box from its points in order.
struct Box {
  Point3 lo, hi;
  template <int N, int M>
  Box(const Point3 (&first)[N], const Point3 (&second)[M]) {
    Point3 l1, h1, l2, h2;
    bounds(first, l1, h1);
    bounds(second, l2, h2);
    lo = {std::max(l1.x, l2.x), std::max(l1.y, l2.y), std::max(l1.z, l2.z)};
    hi = {std::min(h1.x, h2.x), std::min(h1.y, h2.y), std::min(h1.z, h2.z)};
  }
  template <int N>
  static void bounds(const Point3 (&points)[N], Point3& l, Point3& h) {
    l = h = points[0];
    for (int k = 1; k < N; ++k) {
      const Point3 p = points[k];
      l = {std::min(l.x, p.x), std::min(l.y, p.y), std::min(l.z, p.z)};
      h = {std::max(h.x, p.x), std::max(h.y, p.y), std::max(h.z, p.z)};
    }
  }
};

// A vertex of the piece with the planes it lies on. Plain doubles rather than a Point3 (whose members are
// zero-initialized): clip's array of 32 is then not cleared on every call.
struct Candidate {
  double x, y, z;
  unsigned planes;
  Point3 p() const { return {x, y, z}; }
};

// Orders the vertices of face plane `plane` (indices in list[0..m)) around the face by floating-point
// angles in the projection along the dominant axis of the normal: the guard for plane sets that do not
// form one cycle (not seen for finite input).
void order_by_angles(const Point3* v, int* list, int m, Point3 normal) {
  const double ax = std::fabs(normal.x), ay = std::fabs(normal.y), az = std::fabs(normal.z);
  const int axis = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  auto uv = [axis](Point3 p) { return axis == 0 ? Point{p.y, p.z} : axis == 1 ? Point{p.z, p.x} : Point{p.x, p.y}; };
  Point mean{0, 0};
  for (int k = 0; k < m; ++k) mean = mean + (1.0 / m) * uv(v[list[k]]);
  std::sort(list, list + m, [&](int i, int j) {
    const Point pi = uv(v[i]) - mean, pj = uv(v[j]) - mean;
    return std::atan2(pi.y, pi.x) < std::atan2(pj.y, pj.x);
  });
}

// The piece from its vertices and their plane sets: vertices sorted lexicographically, each face's cycle
// from the shared planes. normal(plane) gives a normal of a plane for the guard.
template <class Normal>
Piece3 assemble(const Candidate* c, int n, Normal&& normal) {
  Piece3 out;
  // An index sort (moving 32-byte candidates cost more than comparing them).
  int order[32];
  for (int k = 0; k < n; ++k) order[k] = k;
  for (int k = 1; k < n; ++k)
    for (int m = k; m > 0 && lex_less_flat(c[order[m]].p(), c[order[m - 1]].p()); --m) std::swap(order[m], order[m - 1]);
  out.n = std::min(n, Piece3::kMaxVertices);
  for (int k = 0; k < out.n; ++k) {
    out.v[k] = c[order[k]].p();
    out.planes[k] = static_cast<unsigned char>(c[order[k]].planes);
  }
  const unsigned char* planes = out.planes;
  // on[plane]: the vertices on that plane (bit k for vertex k); count[plane] how many.
  unsigned on[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int count[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int k = 0; k < out.n; ++k)
    for (unsigned p = planes[k]; p != 0; p &= p - 1) {
      const int plane = __builtin_ctz(p);
      on[plane] |= 1u << k;
      ++count[plane];
    }
  // shares[k]: the other vertices on at least two of vertex k's planes (each plane's vertices met again).
  // On a face plane both lie on, two vertices are neighbours around it iff they share another plane, i.e.
  // iff they share two.
  unsigned shares[Piece3::kMaxVertices];
  for (int k = 0; k < out.n; ++k) {
    unsigned seen = 0, twice = 0;
    for (unsigned p = planes[k]; p != 0; p &= p - 1) {
      const unsigned here = on[__builtin_ctz(p)];
      twice |= seen & here;
      seen |= here;
    }
    shares[k] = twice & ~(1u << k);
  }
  int used = 0;
  for (int plane = 0; plane < 8; ++plane) {
    const unsigned face = on[plane];
    const int m = count[plane];
    if (m < 3 || out.faces == Piece3::kMaxFaces || used + m > Piece3::kMaxFaceIndices) continue;
    // The cycle: from the first vertex to its lower-numbered neighbour, then on to the neighbour that is
    // not the previous vertex; every vertex must have exactly two neighbours. v's neighbours on this face:
    // the other vertices of the face that share another plane with v (face & shares[v]).
    unsigned char* cycle = out.face_index + used;
    const int first = __builtin_ctz(face);
    bool ok = true;
    int length = 0, previous = -1, current = first;
    while (length < m) {
      cycle[length++] = static_cast<unsigned char>(current);
      const unsigned found = face & shares[current], second = found & (found - 1);
      if (found == 0 || second == 0 || (second & (second - 1)) != 0) {  // not exactly two
        ok = false;
        break;
      }
      const int n0 = __builtin_ctz(found), n1 = __builtin_ctz(second);  // n0 < n1
      const int next = n0 == previous ? n1 : n0;  // n0 from the first vertex (previous -1)
      if ((previous >= 0) & (n0 != previous) & (n1 != previous)) {  // one predictable branch
        ok = false;
        break;
      }
      previous = current;
      current = next;
    }
    ok = ok && length == m && current == first;
    if (!ok) {
      out.exact = false;
      int list[Piece3::kMaxVertices], k = 0;
      for (unsigned v = face; v != 0; v &= v - 1) list[k++] = __builtin_ctz(v);
      order_by_angles(out.v, list, m, normal(plane));
      for (k = 0; k < m; ++k) cycle[k] = static_cast<unsigned char>(list[k]);
    }
    used += m;
    out.face_vertices[out.faces] = face;
    out.face_start[++out.faces] = used;
  }
  return out;
}

Point3 face_normal(const Point3 t[4], int i) {
  const Point3 p = t[kFace[i][0]], q = t[kFace[i][1]], r = t[kFace[i][2]];
  return cross(q - p, r - p);
}

// 2^-e with 2^e about the largest |coordinate| of the points: scaling by it is exact (unless a coordinate
// falls below 2^-1022 on the way) and keeps the determinants below representable at any scale (clamped
// so that the factor itself is a normal double).
template <int N>
inline double unit_scale(const Point3 (&points)[N]) {
  double m = 0;
  for (const Point3& v : points) m = std::max(std::max(m, std::fabs(v.x)), std::max(std::fabs(v.y), std::fabs(v.z)));
  // e as frexp gives it (m = f 2^e, 0.5 <= f < 1), from m's exponent field: field - 1022 for a normal m,
  // at most -1022 (clamped to -1000) for a subnormal one, 0 for 0 and for inf; then 2^-e from its field.
  std::uint64_t bits;
  std::memcpy(&bits, &m, sizeof bits);
  const int field = static_cast<int>(bits >> 52) & 0x7FF;
  const int e = field == 0 ? (m == 0 ? 0 : -1000) : field == 0x7FF ? 0 : std::min(1000, std::max(-1000, field - 1022));
  const std::uint64_t scale_bits = static_cast<std::uint64_t>(1023 - e) << 52;
  double scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return scale;
}

// The point p + t (q - p) = q + (1 - t) (p - q), t = vp / (vp - vq), for the signed distances vp, vq (of
// opposite signs) of p and q from the line or plane crossed: from the endpoint nearer to it.
// Selections rather than a branch (which end is nearer is data, not predictable).
inline Point3 between(Point3 p, Point3 q, double vp, double vq) {
  const bool from_p = std::fabs(vp) <= std::fabs(vq);
  const Point3 a{from_p ? p.x : q.x, from_p ? p.y : q.y, from_p ? p.z : q.z},
      b{from_p ? q.x : p.x, from_p ? q.y : p.y, from_p ? q.z : p.z};
  const double va = from_p ? vp : vq, vb = from_p ? vq : vp;
  const double t = std::min(1.0, std::max(0.0, va / (va - vb)));  // also maps NaN to 0
  return a + t * (b - a);
}

}  // namespace

Point3 crossing(Point3 p, Point3 q, Point3 x, Point3 y, Point3 z) {
  sort2(p, q);
  sort3(x, y, z);
  // The signed volumes vp = det [y - x, z - x, p - x] and vq have opposite signs, so vp - vq does not
  // cancel; t = vp / (vp - vq) is accurate when both are. Each is evaluated in floating point with its
  // error bound, on coordinates scaled near 1 so that nothing overflows; exactly when the bounds exceed
  // 2^-44 of |vp| + |vq| (an edge nearly parallel to the plane, a thin face, tiny differences), on the
  // coordinates themselves (the scaling rounds subnormal ones) and in units of the larger, however far
  // below the doubles the two lie.
  const Point3 segment[2] = {p, q}, face[3] = {x, y, z};
  const double k = unit_scale({p, q, x, y, z});
  const Point3 sp = k * p, sq = k * q, sx = k * x, sy = k * y, sz = k * z;
  double bp, bq;
  double vp = orient3d_estimate(sx, sy, sz, sp, bp), vq = orient3d_estimate(sx, sy, sz, sq, bq);
  if (!(bp + bq <= 0x1p-44 * (std::fabs(vp) + std::fabs(vq))))
    to_common_scale(orient3d_value(x, y, z, p), orient3d_value(x, y, z, q), vp, vq);
  // The crossing lies on the segment and in the face: the boxes' intersection bounds it.
  const Box box(segment, face);
  return clamp_to(between(p, q, vp, vq), box.lo, box.hi);
}

Point3 crossing(Point3 p, Point3 q, Point3 r, Point3 s) {
  sort2(p, q);
  sort2(r, s);
  if (lex_less(r, p) || (r == p && lex_less(s, q))) {
    std::swap(p, r);
    std::swap(q, s);
  }
  // In the common plane, seen along the axis where its normal is largest (any axis with a non-zero
  // component keeps orientations; the largest keeps them best conditioned): t = op / (op - oq) with op,
  // oq the orientations of p and q against the line r s (opposite signs), estimated or exact as above.
  const Point3 first[2] = {p, q}, second[2] = {r, s};
  const double k = unit_scale({p, q, r, s});
  const Point3 sp = k * p, sq = k * q, sr = k * r, ss = k * s;
  const Point3 n1 = cross(sq - sp, sr - sp), n2 = cross(sq - sp, ss - sp);
  const Point3 n = dot(n1, n1) >= dot(n2, n2) ? n1 : n2;
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  const int axis = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  auto drop = [axis](Point3 v) { return axis == 0 ? Point{v.y, v.z} : axis == 1 ? Point{v.z, v.x} : Point{v.x, v.y}; };
  double bp, bq;
  double op = orient2d_estimate(drop(sr), drop(ss), drop(sp), bp), oq = orient2d_estimate(drop(sr), drop(ss), drop(sq), bq);
  if (!(bp + bq <= 0x1p-44 * (std::fabs(op) + std::fabs(oq))))
    to_common_scale(orient2d_value(drop(r), drop(s), drop(p)), orient2d_value(drop(r), drop(s), drop(q)), op, oq);
  const Box box(first, second);
  return clamp_to(between(p, q, op, oq), box.lo, box.hi);
}

Piece3 clip(const Point3 a[4], const Point3 b[4]) {
  unsigned beyond;
  return clip(a, b, beyond);
}

Piece3 clip(const Point3 a[4], const Point3 b[4], unsigned& beyond) {
  TetFaces a_faces;
  a_faces.set(a);
  return clip(a, a_faces, b, beyond);
}

namespace {

// A whole tetrahedron t (a: shift 0, b: 4): its own vertices, face j the other three (no sorting, no walk).
Piece3 whole(const Point3 t[4], int shift) {
  Piece3 out;
  out.n = 4;
  out.faces = 4;
  for (int i = 0; i < 4; ++i) {
    out.v[i] = t[i];
    out.planes[i] = static_cast<unsigned char>(faces_at_vertex(i) << shift);
    for (int k = 0; k < 3; ++k) out.face_index[3 * i + k] = static_cast<unsigned char>(kFace[i][k]);
    out.face_vertices[i] = 0xFu & ~(1u << i);
    out.face_start[i + 1] = 3 * (i + 1);
  }
  return out;
}

// crossing(), through memo when there is one: tags 0-3 a's face i crossed by b's edge [p, q]; 4-9 a's edge
// e crossing b's face (x, y, z); 10-15 a's edge e crossing b's edge [x, y]. b's points in the key sorted
// (crossing() is a function of the sets).
Point3 crossing_of_b_edge(ClipMemo3* memo, int i, Point3 p, Point3 q, Point3 x, Point3 y, Point3 z) {
  if (!memo) return crossing(p, q, x, y, z);
  sort2(p, q);
  const Point3 key[2] = {p, q};
  Point3 out;
  int slot;
  std::uint64_t hash;
  if (memo->find(i, key, 2, out, slot, hash)) return out;
  out = crossing(p, q, x, y, z);
  memo->store(slot, hash, i, key, 2, out);
  return out;
}

Point3 crossing_of_b_face(ClipMemo3* memo, int e, Point3 p, Point3 q, Point3 x, Point3 y, Point3 z) {
  if (!memo) return crossing(p, q, x, y, z);
  sort3(x, y, z);
  const Point3 key[3] = {x, y, z};
  Point3 out;
  int slot;
  std::uint64_t hash;
  if (memo->find(4 + e, key, 3, out, slot, hash)) return out;
  out = crossing(p, q, x, y, z);
  memo->store(slot, hash, 4 + e, key, 3, out);
  return out;
}

Point3 crossing_of_edges(ClipMemo3* memo, int e, Point3 p, Point3 q, Point3 x, Point3 y) {
  if (!memo) return crossing(p, q, x, y);
  sort2(x, y);
  const Point3 key[2] = {x, y};
  Point3 out;
  int slot;
  std::uint64_t hash;
  if (memo->find(10 + e, key, 2, out, slot, hash)) return out;
  out = crossing(p, q, x, y);
  memo->store(slot, hash, 10 + e, key, 2, out);
  return out;
}

// An exact orientation sign (asked when the filter cannot decide), through memo when there is one: the sign
// kept under (tag, the m points of b in key) when found, else exact() stored there.
template <class Exact>
int memo_sign(ClipMemo3* memo, int tag, const Point3* key, int m, Exact&& exact) {
  if (!memo) return exact();
  Point3 kept;
  int slot;
  std::uint64_t hash;
  if (memo->find(tag, key, m, kept, slot, hash)) return static_cast<int>(kept.x);
  const int s = exact();
  memo->store(slot, hash, tag, key, m, Point3{static_cast<double>(s), 0, 0});
  return s;
}

// sign(x) of b's face plane f against a's vertex i: tags 16-19, the key f's points sorted (an odd
// permutation of them flips the orientation).
int face_side(ClipMemo3* memo, const PlaneSide& f, int i, Point3 x) {
  const int s = f.filter(x);
  if (s != 0) return s;
  Point3 key[3] = {f.p, f.q, f.r};
  int parity = 1;
  auto order = [&parity](Point3& u, Point3& v) {
    if (lex_less(v, u)) {
      std::swap(u, v);
      parity = -parity;
    }
  };
  order(key[0], key[1]);
  order(key[1], key[2]);
  order(key[0], key[1]);
  return parity * memo_sign(memo, 16 + i, key, 3, [&] { return orient3d_exact(key[0], key[1], key[2], x); });
}

// sign(x) of a's face plane f (face i) against b's vertex x: tags 20-23, the key x.
int vertex_side(ClipMemo3* memo, const PlaneSide& f, int i, Point3 x) {
  const int s = f.filter(x);
  return s != 0 ? s : memo_sign(memo, 20 + i, &x, 1, [&] { return orient3d_exact(f.p, f.q, f.r, x); });
}

// orient3d(p, q, x, y) for a's edge e = [p, q] and b's edge [x, y]: tags 24-29, the key x, y sorted
// (swapping them flips the sign).
int edge_orientation(ClipMemo3* memo, int e, Point3 p, Point3 q, Point3 x, Point3 y) {
  const int s = orient3d_filter(p, q, x, y);
  if (s != 0) return s;
  int flip = 1;
  if (lex_less(y, x)) {
    std::swap(x, y);
    flip = -1;
  }
  const Point3 key[2] = {x, y};
  return flip * memo_sign(memo, 24 + e, key, 2, [&] { return orient3d_exact(p, q, x, y); });
}

}  // namespace

Piece3 clip(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], unsigned& beyond, ClipMemo3* memo) {
  beyond = 0;
  TetFaces b_faces;
  b_faces.set(b);
  auto normal = [&](int plane) { return plane < 4 ? face_normal(a, plane) : face_normal(b, plane - 4); };
  Candidate c[32];
  int n = 0;
  // pos_b[j], neg_b[j]: the vertices of a strictly on the inner, outer side of b's face j (bit i); pos_a,
  // neg_a the same for b's vertices and a's faces; side_b[j][i], side_a[i][j] the same signs (+1, 0, -1) as a table.
  unsigned pos_b[4], neg_b[4], pos_a[4], neg_a[4];
  int side_b[4][4], side_a[4][4];
  for (int j = 0; j < 4; ++j) {
    pos_b[j] = neg_b[j] = 0;
    for (int i = 0; i < 4; ++i) {
      const int side = side_b[j][i] = face_side(memo, b_faces.face[j], i, a[i]);
      pos_b[j] |= static_cast<unsigned>(side > 0) << i;
      neg_b[j] |= static_cast<unsigned>(side < 0) << i;
    }
    if (pos_b[j] == 0) return Piece3{};  // face j's plane separates
    if (neg_b[j] != 0) beyond |= 1u << j;
  }
  if (beyond == 0) return whole(a, 0);  // a in closed b
  bool b_inside = true;
  for (int i = 0; i < 4; ++i) {
    pos_a[i] = neg_a[i] = 0;
    for (int j = 0; j < 4; ++j) {
      const int side = side_a[i][j] = vertex_side(memo, a_faces.face[i], i, b[j]);
      pos_a[i] |= static_cast<unsigned>(side > 0) << j;
      neg_a[i] |= static_cast<unsigned>(side < 0) << j;
    }
    if (pos_a[i] == 0) return Piece3{};
    if (neg_a[i] != 0) b_inside = false;
  }
  if (b_inside) return whole(b, 4);

  auto add = [&](Point3 p, unsigned planes) {
    if (n < 32) c[n++] = {p.x, p.y, p.z, planes};
  };
  // Vertices of a in closed b: on a's three faces at the vertex and on b's faces where the side is 0.
  const unsigned a_outside = neg_b[0] | neg_b[1] | neg_b[2] | neg_b[3];
  for (int i = 0; i < 4; ++i) {
    if (a_outside >> i & 1u) continue;
    unsigned planes = faces_at_vertex(i);
    for (int j = 0; j < 4; ++j)
      if (side_b[j][i] == 0) planes |= 1u << (4 + j);
    add(a[i], planes);
  }
  // Vertices of b in closed a that are not vertices of a.
  const unsigned b_outside = neg_a[0] | neg_a[1] | neg_a[2] | neg_a[3];
  for (int j = 0; j < 4; ++j) {
    if (b_outside >> j & 1u) continue;
    if (b[j] == a[0] || b[j] == a[1] || b[j] == a[2] || b[j] == a[3]) continue;
    unsigned planes = faces_at_vertex(j) << 4;
    for (int i = 0; i < 4; ++i)
      if (side_a[i][j] == 0) planes |= 1u << i;
    add(b[j], planes);
  }
  // The orientations of a's edge lines against b's: edge(ea) of a, edge(eb) of b,
  // orient3d(a[p], a[q], b[x], b[y]) = orient3d(b[x], b[y], a[p], a[q]) (an even permutation).
  signed char table[6][6];
  for (auto& row : table)
    for (auto& t : row) t = 2;  // not computed yet
  auto orientation = [&](int ea, int eb) {
    signed char& t = table[ea][eb];
    if (t == 2)
      t = static_cast<signed char>(edge_orientation(memo, ea, a[kEdge[ea][0]], a[kEdge[ea][1]], b[kEdge[eb][0]], b[kEdge[eb][1]]));
    return static_cast<int>(t);
  };
  // An edge crossing the plane of a face (k, l, m) of the other tetrahedron strictly: the crossing's sides
  // of that tetrahedron's other three face planes (crossing_side) say where it passes: all inside, through
  // the open face; on one of them and inside the other two, through the open edge where that plane meets the
  // face; on two, through a vertex (found above as a vertex in the other tetrahedron).
  unsigned long long edge_pairs = 0;  // the edge-edge crossings already added, bit 6 * ea + eb
  for (unsigned pairs = crossing_pairs(pos_b, neg_b); pairs != 0; pairs &= pairs - 1) {
    const int at = __builtin_ctz(pairs), ea = at >> 2, j = at & 3;
    const int p = kEdge[ea][0], q = kEdge[ea][1];
    const int k = kFace[j][0], l = kFace[j][1], m = kFace[j][2];
    // edge z of face j: b's edge eb[z], where the plane of b's face opposite[z] meets face j
    const int eb[3] = {kEdgeIndex[k][l], kEdgeIndex[l][m], kEdgeIndex[k][m]}, opposite[3] = {m, k, l};
    int zeros = 0, zero = -1;
    bool inside = true;
    for (int z = 0; z < 3 && inside; ++z) {
      const int o = opposite[z];
      const int side = crossing_side(side_b[o][p], side_b[o][q], side_b[j][p], kPermutationSign[j][o],
                                     [&] { return orientation(ea, eb[z]); });
      if (side < 0) inside = false;
      if (side == 0) ++zeros, zero = z;
    }
    if (!inside) continue;
    if (zeros == 0) {
      add(crossing_of_b_face(memo, ea, a[p], a[q], b[k], b[l], b[m]), faces_at_edge(p, q) | 1u << (4 + j));
    } else if (zeros == 1) {
      const unsigned long long bit = 1ull << (6 * ea + eb[zero]);
      if (edge_pairs & bit) continue;
      edge_pairs |= bit;
      const int x = kEdge[eb[zero]][0], y = kEdge[eb[zero]][1];
      add(crossing_of_edges(memo, ea, a[p], a[q], b[x], b[y]), faces_at_edge(p, q) | faces_at_edge(x, y) << 4);
    }
  }
  // b's edges through a's open faces (the edge-edge crossings were all found from a's side: an edge of a
  // crossing an open edge of b strictly crosses the plane of a face of b at that edge).
  for (unsigned pairs = crossing_pairs(pos_a, neg_a); pairs != 0; pairs &= pairs - 1) {
    const int at = __builtin_ctz(pairs), eb = at >> 2, i = at & 3;
    const int x = kEdge[eb][0], y = kEdge[eb][1];
    const int k = kFace[i][0], l = kFace[i][1], m = kFace[i][2];
    const int ea[3] = {kEdgeIndex[k][l], kEdgeIndex[l][m], kEdgeIndex[k][m]}, opposite[3] = {m, k, l};
    bool inside = true;
    for (int z = 0; z < 3 && inside; ++z) {
      const int o = opposite[z];
      inside = crossing_side(side_a[o][x], side_a[o][y], side_a[i][x], kPermutationSign[i][o],
                             [&] { return orientation(ea[z], eb); }) > 0;
    }
    if (inside) add(crossing_of_b_edge(memo, i, b[x], b[y], a[k], a[l], a[m]), faces_at_edge(x, y) << 4 | 1u << i);
  }
  if (n < 4) return Piece3{};  // the interiors do not meet (touching along a segment or at a point)
  // A face plane of b that is a face plane of a too (same side: opposite sides separate) keeps a's bit.
  for (int i = 0; i < 4; ++i) {
    const unsigned on_plane = 0xFu & ~(pos_a[i] | neg_a[i]);  // b's vertices on the plane of a's face i
    const unsigned one_cleared = on_plane & (on_plane - 1);  // its lowest bit cleared
    if ((one_cleared & (one_cleared - 1)) == 0) continue;    // fewer than 3 of b's vertices on it
    for (int j = 0; j < 4; ++j)
      if ((on_plane | 1u << j) == 0xFu)  // b's face j (its vertices but j) lies in that plane
        for (int k = 0; k < n; ++k) c[k].planes &= ~(1u << (4 + j));
  }
  return assemble(c, n, normal);
}

namespace {

// A vertex of the polytope that clip_filtered cuts down from a, one face plane of b at a time. While every
// side is certified the polytope is simple: each vertex lies on exactly three of its face planes and has
// three neighbours, listed in the same rotational sense at every vertex, so that a face is walked by
// turning the same way at each vertex: arriving at w from u = w.nb[i], go on to w.nb[(i + 1) % 3].
struct SimpleVertex {
  double x, y, z;     // plain doubles (a Point3 is zero-initialized): the polytope's 32 are not cleared
  double d[4], e[4];  // orient3d values against b's face planes (TetFaces' sign convention), error bounds
  int nb[3];
  int back[3];      // where this vertex is in its neighbours' lists: v_[nb[s]].nb[back[s]] is this one
  unsigned planes;  // as Piece3::planes
  Point3 p() const { return {x, y, z}; }
};

constexpr int kNextSlot[3] = {1, 2, 0};

// a's vertex i's neighbours in the sense det [n0 - v, n1 - v, n2 - v] > 0 (a positively oriented), and
// where i is in their lists.
constexpr int kTetNeighbours[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
constexpr int kTetBack[4][3] = {{0, 0, 0}, {0, 2, 1}, {1, 2, 1}, {2, 2, 1}};
// The largest error bound, relative to |d(u) - d(w)| on the edge being cut, for which the crossing is built
// in floating point: its position along the edge is then within 2^-40 of the edge's length.
constexpr double kMaxRelativeBound = 0x1p-40;
constexpr double kEpsilon = 0x1p-53;

class SimplePolytope {
 public:
  static constexpr int kCapacity = 32;  // at most the bits of live_
  enum Outcome { kKept, kEmpty, kUncertain };

  // a's vertex i's value against b's plane j and its bound (before start()).
  void set_value(int i, int j, double d, double e) {
    v_[i].d[j] = d;
    v_[i].e[j] = e;
  }
  // Vertex i (of a's four, after start()) lies on plane `plane` too (Piece3::planes' numbering).
  void add_plane(int i, int plane) { v_[i].planes |= 1u << plane; }
  // a's four vertices, their values against b's planes set (set_value).
  void start(const Point3 a[4]) {
    n_ = 4;
    for (int i = 0; i < 4; ++i) {
      SimpleVertex& v = v_[i];
      v.x = a[i].x;
      v.y = a[i].y;
      v.z = a[i].z;
      for (int s = 0; s < 3; ++s) {
        v.nb[s] = kTetNeighbours[i][s];
        v.back[s] = kTetBack[i][s];
      }
      v.planes = faces_at_vertex(i);
    }
    live_ = 0xFu;
  }

  // Keeps the part on the inner side of b's plane j (d > 0). Each value's sign is certified (|d| > e) or the
  // outcome is kUncertain. A crossing w = u + t (x - u), t = d(u) / (d(u) - d(x)), of an edge from u inside
  // to x outside gets, for the later planes o, d_o(w) = d_o(u) + t (d_o(x) - d_o(u)) (orient3d is affine in
  // its last point, so the exact crossing's value is this combination with the exact t), with the bound
  // max(e_o(u), e_o(x)) + dt |d_o(x) - d_o(u)| + 4 eps (|d_o(u)| + |d_o(x)|), dt >= |t - t_exact|:
  // |t - t_exact| <= (e(u) + e(x)) / (d(u) - d(x)) to first order (both ends' values within their bounds),
  // plus 3 eps for t's own rounding.
  // The cut by plane j; the values and bounds carried to the new vertices are those of the planes that cut
  // later (bit m of later, m > j; j a template argument: a fixed loop over the planes after it). The others'
  // are left unset: no cut reads them.
  // inside4, outside4: a's vertices (0-3) certainly inside and outside plane j, already known (bit i).
  Outcome cut(int j, unsigned inside4, unsigned outside4, unsigned later) {
    switch (j) {
      case 0: return cut_by<0>(inside4, outside4, later);
      case 1: return cut_by<1>(inside4, outside4, later);
      case 2: return cut_by<2>(inside4, outside4, later);
      default: return cut_by<3>(inside4, outside4, later);
    }
  }

  template <int j>
  Outcome cut_by(unsigned inside4, unsigned outside4, unsigned later) {
    unsigned inside = inside4 & live_, outside = outside4 & live_;  // certified
    for (unsigned live = live_ & ~0xFu; live != 0; live &= live - 1) {  // the crossings made so far
      const int k = __builtin_ctz(live);
      inside |= static_cast<unsigned>(v_[k].d[j] > v_[k].e[j]) << k;
      outside |= static_cast<unsigned>(-v_[k].d[j] > v_[k].e[j]) << k;
    }
    if ((inside | outside) != live_) return kUncertain;
    if (outside == 0) return kKept;
    if (outside == live_) return kEmpty;
    const int old = n_;
    for (; inside != 0; inside &= inside - 1) {
      const int k = __builtin_ctz(inside);
      const int* nb = v_[k].nb;
      unsigned crossed = (outside >> nb[0] & 1u) | (outside >> nb[1] & 1u) << 1 | (outside >> nb[2] & 1u) << 2;
      for (; crossed != 0; crossed &= crossed - 1) {
        const int s = __builtin_ctz(crossed), x = nb[s];
        if (n_ == kCapacity) return kUncertain;
        const SimpleVertex &u = v_[k], &o = v_[x];
        const double du = u.d[j], dx = o.d[j], span = du - dx, error = u.e[j] + o.e[j];
        if (!(error <= kMaxRelativeBound * span)) return kUncertain;
        const double t = du / span, dt = error / (span - error) + 3 * kEpsilon;
        SimpleVertex& w = v_[n_];
        const Point3 crossing = between(u.p(), o.p(), du, dx);
        w.x = crossing.x;
        w.y = crossing.y;
        w.z = crossing.z;
        for (int m = j + 1; m < 4; ++m) {
          if (!(later >> m & 1u)) continue;
          const double change = o.d[m] - u.d[m];
          w.d[m] = u.d[m] + t * change;
          w.e[m] = (std::max(u.e[m], o.e[m]) + dt * std::fabs(change) +
                    4 * kEpsilon * (std::fabs(u.d[m]) + std::fabs(o.d[m]))) * (1 + 0x1p-40);
        }
        w.planes = (u.planes & o.planes) | 1u << (4 + j);
        w.nb[0] = k;
        w.back[0] = s;
        v_[k].nb[s] = n_;
        v_[k].back[s] = 0;
        ++n_;
      }
    }
    // The cap: from each new vertex w, walk the face on one side of its edge into the kept part until the
    // next new vertex c; w and c are neighbours on the cap (w.nb[2] = c, c.nb[1] = w).
    for (int w = old; w < n_; ++w) {
      int current = v_[w].nb[0], slot = kNextSlot[v_[w].back[0]];
      while (current < old) {
        const SimpleVertex& c = v_[current];
        current = c.nb[slot];
        slot = kNextSlot[c.back[slot]];
      }
      v_[w].nb[2] = current;
      v_[w].back[2] = 1;
      v_[current].nb[1] = w;
      v_[current].back[1] = 2;
    }
    // The vertices outside stay in the buffer, dead (at most 4 + 4 + 5 + 6 + 7 = 26 in all: a cut adds one
    // vertex per face it crosses).
    const unsigned made = n_ == 32 ? ~0u : (1u << n_) - 1;  // the vertices made so far (live_ is 32 bits)
    live_ = (live_ & ~outside) | (made & ~((1u << old) - 1));
    return kKept;
  }

  // The piece: a vertex on three of b's planes is b's vertex (the fourth's), exactly; each face is walked
  // once from each of its directed edges' first. False when the piece does not fit Piece3.
  bool to_piece(const Point3 b[4], Piece3& out) const {
    // the live vertices renumbered in order
    int index[kCapacity], n = 0;
    for (unsigned live = live_; live != 0; live &= live - 1) {
      const int k = __builtin_ctz(live);
      if (n == Piece3::kMaxVertices) return false;
      index[k] = n;
      const unsigned of_b = v_[k].planes >> 4;
      out.v[n] = of_b == 0xEu ? b[0] : of_b == 0xDu ? b[1] : of_b == 0xBu ? b[2] : of_b == 0x7u ? b[3] : v_[k].p();
      out.planes[n++] = static_cast<unsigned char>(v_[k].planes);
    }
    out.n = n;
    static_assert(3 * Piece3::kMaxVertices <= Piece3::kMaxFaceIndices, "a face walk's steps fit face_index");
    unsigned walked[kCapacity] = {};  // bit s: the edge from k to its neighbour s
    int used = 0;
    out.faces = 0;
    for (unsigned live = live_; live != 0; live &= live - 1)
      for (int k = __builtin_ctz(live), s = 0; s < 3; ++s) {
        if (walked[k] >> s & 1u) continue;
        if (out.faces == Piece3::kMaxFaces) return false;
        int current = k, slot = s;
        unsigned on = 0;
        // Each step marks one (vertex, neighbour) pair and the walk stops at a marked one: at most 3 n <= 48
        // steps in all, within kMaxFaceIndices.
        do {
          const int i = index[current];
          out.face_index[used++] = static_cast<unsigned char>(i);
          on |= 1u << i;
          walked[current] |= 1u << slot;
          const SimpleVertex& c = v_[current];
          current = c.nb[slot];
          slot = kNextSlot[c.back[slot]];
        } while (!(walked[current] >> slot & 1u));
        out.face_vertices[out.faces] = on;
        out.face_start[++out.faces] = used;
      }
    out.exact = true;
    return true;
  }

 private:
  SimpleVertex v_[kCapacity];
  int n_ = 0;         // vertices made, live or not
  unsigned live_ = 0;  // bit k: vertex k is a vertex of the polytope
};

}  // namespace

namespace {

// Two doubles handled as one value (GCC and Clang vector extensions: one SSE2 register on x86-64, where
// the lane-wise comparisons are cmppd and their masks' sign bits one movmskpd), and the comparisons' masks
// (-1 true, 0 false). a's four vertices are two such pairs.
typedef double Lanes2 __attribute__((vector_size(16)));
typedef long long Mask2 __attribute__((vector_size(16)));
constexpr Mask2 kNoSign = {0x7FFFFFFFFFFFFFFFLL, 0x7FFFFFFFFFFFFFFFLL};
// Bit i set where lane i of m is true (-1).
inline unsigned lane_bits(Mask2 m) {
#if defined(__SSE2__)
  return static_cast<unsigned>(__builtin_ia32_movmskpd(reinterpret_cast<Lanes2>(m)));
#else
  return static_cast<unsigned>(m[0] & 1) | static_cast<unsigned>(m[1] & 1) << 1;
#endif
}
inline Lanes2 magnitude(Lanes2 v) { return reinterpret_cast<Lanes2>(reinterpret_cast<Mask2>(v) & kNoSign); }

// clip_filtered's floating-point path: false when a side is uncertain (then out is unset), else out is the
// piece (n = 0 when empty) and beyond is set.
bool filtered_piece(const Point3 a[4], const Point3 b[4], const TetNormals& b_normals, unsigned& beyond,
                    Piece3& out) {
  // a's vertices by axis, two pairs of lanes (vertices 0, 1 and 2, 3): the values against one plane at once
  const Lanes2 ax[2] = {{a[0].x, a[1].x}, {a[2].x, a[3].x}}, ay[2] = {{a[0].y, a[1].y}, {a[2].y, a[3].y}},
               az[2] = {{a[0].z, a[1].z}, {a[2].z, a[3].z}};
  // the values and bounds go straight to the polytope's first four vertices (start() takes them there)
  SimplePolytope polytope;
  unsigned inner = 0, outer = 0;  // bit 4 j + i: a's vertex i certainly inside, outside b's face j
  unsigned on = 0;                // bit 4 j + i: a's vertex i exactly on b's face plane j (exact planes only)
  unsigned bounded = 0xFu;        // bit i: vertex i's permanents all >= 2^-900 s so far
  beyond = 0;
  out.n = 0;
  const Lanes2 one = {1, 1};
  // a's vertices less the point of b's planes (b[1] for plane 0, b[0] for planes 1-3: TetFaces' p), their
  // magnitudes and the permanents' least value 2^-900 s, per point q and half h
  Lanes2 wx[2][2], wy[2][2], wz[2][2], fx[2][2], fy[2][2], fz[2][2], least[2][2];
  for (int q = 0; q < 2; ++q)
    for (int h = 0; h < 2; ++h) {
      wx[q][h] = ax[h] - b[1 - q].x;
      wy[q][h] = ay[h] - b[1 - q].y;
      wz[q][h] = az[h] - b[1 - q].z;
      fx[q][h] = magnitude(wx[q][h]);
      fy[q][h] = magnitude(wy[q][h]);
      fz[q][h] = magnitude(wz[q][h]);
      least[q][h] = 0x1p-900 * (one + fx[q][h] + fy[q][h] + fz[q][h]);
    }
  for (int j = 0; j < 4; ++j) {
    // PlaneSide::estimate for the four vertices (the same operations in the same order); the bound
    // kRelative permanent of orient3d_bound where permanent >= 2^-900 s, else (tiny or NaN) the exact clip
    const int q = j == 0 ? 0 : 1;
    const Point3 n = b_normals.n(j), pn = b_normals.pn(j);
    // an exact plane (TetNormals::exact): the estimate's sign is the side's, 0 exactly on the plane (its value
    // still carries the bound ej, which the crossings' values inherit)
    const int axis = b_normals.exact[j];
    const Lanes2 sign_bound = axis ? Lanes2{0, 0} : Lanes2{1, 1}, none = {0, 0};
    unsigned in = 0, out_j = 0, on_j = 0;
    for (int h = 0; h < 2; ++h) {
      const Lanes2 dj = wx[q][h] * n.x + wy[q][h] * n.y + wz[q][h] * n.z;
      const Lanes2 permanent = fx[q][h] * pn.x + fy[q][h] * pn.y + fz[q][h] * pn.z;
      const Lanes2 ej = kOrient3dRelativeBound * permanent, cj = ej * sign_bound;
      // on the plane exactly: the coordinate difference is 0 (not the product, which may underflow)
      const unsigned zero = axis == 0   ? 0u
                            : axis == 1 ? lane_bits(wx[q][h] == none)
                            : axis == 2 ? lane_bits(wy[q][h] == none)
                                        : lane_bits(wz[q][h] == none);
      bounded &= (lane_bits(permanent >= least[q][h]) | zero) << (2 * h) | (0x3u << (2 - 2 * h));
      in |= lane_bits(dj > cj) << (2 * h);
      out_j |= lane_bits(-dj > cj) << (2 * h);
      on_j |= zero << (2 * h);
      polytope.set_value(2 * h, j, dj[0], ej[0]);
      polytope.set_value(2 * h + 1, j, dj[1], ej[1]);
    }
    // face j's plane separates (no vertex certainly inside, all certainly outside or on it): empty, whatever the
    // other planes' sides (the interiors do not meet)
    if (in == 0 && (out_j | on_j) == 0xFu && bounded == 0xFu) return true;
    inner |= in << (4 * j);
    outer |= out_j << (4 * j);
    on |= on_j << (4 * j);
  }
  if (bounded != 0xFu) return false;
  if ((inner | outer | on) != 0xFFFFu) return false;  // a side within its bound
  for (int j = 0; j < 4; ++j) beyond |= static_cast<unsigned>((outer >> (4 * j) & 0xFu) != 0) << j;
  if (beyond == 0) {  // a in closed b
    out = whole(a, 0);
    return true;
  }
  // A vertex on a plane that cuts a: the exact clip. On one that does not, the vertex lies on it (its plane set
  // says so), unless three do: then a's face lies in that plane, which keeps a's bit only (as clip()).
  unsigned touching[4] = {0, 0, 0, 0};
  for (int j = 0; j < 4; ++j) {
    const unsigned on_j = on >> (4 * j) & 0xFu;
    if (on_j == 0) continue;
    if (beyond >> j & 1u) return false;
    if (__builtin_popcount(on_j) < 3) touching[j] = on_j;
  }
  polytope.start(a);
  for (int j = 0; j < 4; ++j)
    for (unsigned t = touching[j]; t != 0; t &= t - 1) polytope.add_plane(__builtin_ctz(t), 4 + j);
  for (int j = 0; j < 4; ++j) {
    if (!(beyond >> j & 1u)) continue;
    const SimplePolytope::Outcome o =
        polytope.cut(j, inner >> (4 * j) & 0xFu, outer >> (4 * j) & 0xFu, beyond & ~((2u << j) - 1));
    if (o == SimplePolytope::kEmpty) return true;
    if (o == SimplePolytope::kUncertain) return false;
  }
  return polytope.to_piece(b, out);
}

}  // namespace

Piece3 clip_filtered(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], unsigned& beyond,
                     ClipMemo3* memo) {
  TetNormals b_normals;
  b_normals.set(b);
  return clip_filtered(a, a_faces, b, b_normals, beyond, memo);
}

Piece3 clip_filtered(const Point3 a[4], const TetFaces& a_faces, const Point3 b[4], const TetNormals& b_normals,
                     unsigned& beyond, ClipMemo3* memo) {
  Piece3 out;  // the one object returned (no copy)
  if (!filtered_piece(a, b, b_normals, beyond, out)) out = clip(a, a_faces, b, beyond, memo);
  return out;
}

}  // namespace dlmfsi
