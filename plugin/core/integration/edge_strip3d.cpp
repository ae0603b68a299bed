// The band near a fluid edge (PointIntegrator3::edge_strips): gather_band's columns of a fluid face F start on the
// straight preimage of F's plane (a = n . A - c = 0) and are kept where their start's image lies in F. The band's
// true integrand is f of the fluid tetrahedron holding X(s); going from A(s) to X(s) along the segment between them
// it changes by each fluid face's jump where the segment crosses that face, so F's jump J_F belongs to the points s
// where the segment crosses F's plane (a and q = n . X - c of opposite signs) at a point
//   Y*(s) = (a X(s) - q A(s)) / (a - q)
// of F, not where the column's start does. The two differ only near F's edges: on a column starting at xi0 with
// root l, Y* runs from A(xi0) (t = 0, a = 0) to X(xi0 + l d) (t = l, q = 0); where those two lie on opposite
// sides of F's edge e (g = 0, g = n_G . (y - p) for kf's other face G through e: negative inside), the column's
// points past t_c, the root of g(Y*(t)), cross the plane beyond e. The starts xi0 where that happens form a strip
// along e on the start plane, between the wall g(A(xi0)) = 0 and the curve g(X(xi0 + l(xi0) d)) = 0, of the band's
// thickness. Where the strip lies inside F (its start in F, Y* beyond e), those points cross the face F2 beyond e
// in F's plane (the fluid face coplanar with F across e), whose jump replaces F's: J_F2 - J_F from t_c to l; where
// no face of the plane lies beyond e, -J_F. Where the strip lies beyond e (start beyond, Y* in F), F2's own strip
// does it; with no F2, +J_F. Over the strip, in (u, v) (u along the edge, v = -g(A(xi0)) across it) and t, the
// integrand is smooth: Gauss-Legendre in all three. Data whose jumps add up (J_F2 = J_F) get nothing.
// What is left is of the next order in the band's thickness: near F's corners, where two edges' strips overlap,
// where a strip's columns cross the solid tetrahedron's faces (they go on with its polynomials), and where the
// piece's face lies on the sub-tetrahedron's boundary (no strip there).
#include <algorithm>
#include <cmath>

#include "fe/rules.hpp"
#include "geometry/predicates3d.hpp"
#include "integration/integrate_points3d.hpp"
#include "integration/reference_tet.hpp"
#include "sides/sides3d.hpp"

namespace dlmfsi {

namespace {

// The root of h on the interval between 0 and l where h(0) and h(l) have opposite signs (Illinois' false
// position, to 1e-12 of l: the strip's integrand vanishes where t_c = l, so its error there is of second order).
template <class H>
double bracketed_root(H&& h, double l, double h0, double hl) {
  double lo = 0, hi = l, f_lo = h0, f_hi = hl;
  int side = 0;
  for (int it = 0; it < 60; ++it) {
    const double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(std::fabs(hi - lo) > 1e-12 * std::fabs(l)) || !std::isfinite(t)) break;
    const double f = h(t);
    if (f == 0) return t;
    if ((f < 0) == (f_lo < 0)) {
      lo = t;
      f_lo = f;
      if (side == -1) f_hi /= 2;
      side = -1;
    } else {
      hi = t;
      f_hi = f;
      if (side == 1) f_lo /= 2;
      side = 1;
    }
  }
  return std::fabs(f_lo) < std::fabs(f_hi) ? lo : hi;
}

}  // namespace

Point3 PointIntegrator3::straight_slope(Point3 w) const {
  const StraightImage& a = straight_;
  return (dot(w, a.cofactor[0]) / a.det) * a.ey[0] + (dot(w, a.cofactor[1]) / a.det) * a.ey[1] +
         (dot(w, a.cofactor[2]) / a.det) * a.ey[2];
}

// grad_xi (n . A) = E_xi^-T E_y^T n: z . ex[i] = (E_y^T n)_i, by the cofactors of E_xi.
Point3 PointIntegrator3::straight_gradient(Point3 n) const {
  const StraightImage& a = straight_;
  const Point3 w{dot(a.ey[0], n), dot(a.ey[1], n), dot(a.ey[2], n)};  // E_y^T n
  return (1 / a.det) * (w.x * a.cofactor[0] + w.y * a.cofactor[1] + w.z * a.cofactor[2]);
}

Point3 PointIntegrator3::straight_position(const ClippedImage3& image, Point3 xi) const {
  return (image.sub_y[0] - image.origin) + straight_slope(xi - image.sub_xi[0]);
}

void PointIntegrator3::edge_strips(const ClippedImage3& image, int kf, int j, const Piece3& piece, int f,
                                   const Point3* xi_corner, double solid_det, const BandFace& face, Point3 n,
                                   double rise, double height) {
  const int s = piece.face_start[f], e = piece.face_start[f + 1], m = e - s;
  // A point inside the face (its vertices' mean: the face is convex), which tells the strips' side of each edge.
  Point3 inside;
  for (int i = 0; i < m; ++i) inside = inside + xi_corner[piece.face_index[s + i]];
  inside = (1.0 / m) * inside;
  // Lengths of round-off: where a fluid edge passes within round-off of a sub-tetrahedron's edge, the clip can leave
  // two vertices 1e-16 apart, and the direction between them is noise. Against the sub-tetrahedron's size in xi (its
  // longest edge), an edge shorter than 1e-12 of it carries no strip (the strip would be as short), and an end whose
  // next edge is that short takes none, as an end on an edge of length zero does: a strip along such an edge, or
  // with an end along one, would cover an area that has nothing to do with the face (coupling3d_curved_roundoff.edp).
  const double tiny2 = 1e-24 * straight_.size2;
  auto fluid_vertex = [&piece](int v) { return __builtin_popcount(piece.planes[v] & 0xF0u) >= 3; };
  // Each end's direction across the edge: along the piece's next edge where the segment ends on a face of the
  // sub-tetrahedron (so that the strips of the sub-tetrahedra on either side meet there), none (across, in the
  // plane) where it ends at a fluid vertex (so that the strips of the faces on either side of the edge cover
  // the same region).
  auto end_direction = [&](int v, int next) {
    const Point3 d = xi_corner[next] - xi_corner[v];
    return fluid_vertex(v) || !(dot(d, d) > tiny2) ? Point3() : d;
  };
  for (int i = 0; i < m; ++i) {
    const int va = piece.face_index[s + i], vb = piece.face_index[s + (i + 1) % m];
    // the piece's edge on another face plane of kf: along F's edge with that face G
    const unsigned others = piece.planes[va] & piece.planes[vb] & 0xF0u & ~(1u << (4 + j));
    if (others == 0 || (others & (others - 1)) != 0) continue;
    const Point3 along = xi_corner[vb] - xi_corner[va];
    if (!(dot(along, along) > tiny2)) continue;
    const int vp = piece.face_index[s + (i + m - 1) % m], vn = piece.face_index[s + (i + 2) % m];
    const Point3 ends[2] = {end_direction(va, vp), end_direction(vb, vn)};
    edge_strip(image, kf, j, __builtin_ctz(others) - 4, piece.v[va], xi_corner[va], xi_corner[vb], inside, ends,
               solid_det, face, n, rise, height);
  }
}

bool PointIntegrator3::coplanar_beyond(int kf, int j, int g_face, int& same, int& other) const {
  constexpr int kSlots = 1024;
  if (beyond_.empty()) beyond_.resize(kSlots);
  const unsigned key = 16u * static_cast<unsigned>(kf) + 4u * static_cast<unsigned>(j) + static_cast<unsigned>(g_face);
  Beyond& kept = beyond_[key % kSlots];
  if (kept.kf == kf && kept.j == j && kept.g_face == g_face) {
    same = kept.same;
    other = kept.other;
    return kept.found;
  }
  same = other = -1;
  kept.found = walk_beyond(kf, j, g_face, same, other);
  kept.kf = kf;
  kept.j = j;
  kept.g_face = g_face;
  kept.same = same;
  kept.other = other;
  return kept.found;
}

bool PointIntegrator3::walk_beyond(int kf, int j, int g_face, int& same, int& other) const {
  const Mesh3& mesh = fluid_->mesh();
  Point3 plane[3];
  for (int m = 0; m < 3; ++m) plane[m] = mesh.vertex(kf, (j + 1 + m) & 3);
  // e's ends: kf's vertices but j and g_face
  int ends[2], n = 0;
  for (int i = 0; i < 4; ++i)
    if (i != j && i != g_face) ends[n++] = mesh.tetrahedra[kf][i];
  const int f_vertex = mesh.tetrahedra[kf][g_face];  // F's vertex off e
  // around e from kf through G, on kf's side of F's plane until a face of the ring lies in it
  int t = kf, through = g_face;
  for (int step = 0; step < 64; ++step) {
    // the face of t opposite vertex `through` holds e; its vertex off e
    int third = -1;
    for (int i = 0; i < 4; ++i) {
      const int v = mesh.tetrahedra[t][i];
      if (i != through && v != ends[0] && v != ends[1]) third = i;
    }
    if (third < 0 || mesh.tetrahedra[t][third] == f_vertex) return false;  // back at F, from across it
    if (t != kf || through != g_face) {  // G itself is not in F's plane
      if (orient3d(plane[0], plane[1], plane[2], mesh.vertex(t, third)) == 0) {
        same = t;
        other = mesh.neighbours[t][through];
        return true;
      }
    }
    const int next = mesh.neighbours[t][through];
    if (next < 0 || next == kf) return false;
    // in next, the face holding e other than the one shared with t
    int back = -1, on = -1;
    for (int i = 0; i < 4; ++i) {
      const int v = mesh.tetrahedra[next][i];
      if (v == ends[0] || v == ends[1]) continue;
      if (mesh.neighbours[next][i] == t) back = i;
      else on = i;
    }
    if (back < 0 || on < 0) return false;
    t = next;
    through = on;
  }
  return false;
}

void PointIntegrator3::edge_strip(const ClippedImage3& image, int kf, int j, int g_face, Point3 y_edge, Point3 xi_a,
                                  Point3 xi_b, Point3 xi_in, const Point3 (&ends)[2], double solid_det,
                                  const BandFace& face, Point3 n, double rise, double height) {
  const Point3 n_g = face_normal(kf, g_face);  // g(y) = n_g . (y - y_edge): negative inside kf
  auto g = [&](Point3 y) { return dot(n_g, y - y_edge); };
  // w: across the edge in the start plane (a = 0: the plane's preimage under A, normal grad_xi a), towards the
  // piece, scaled so that g(A) falls by 1 per unit of v
  const Point3 along = xi_b - xi_a;
  const Point3 z = straight_gradient(n);
  Point3 across = cross(z, along);
  if (dot(across, xi_in - xi_a) < 0) across = -1.0 * across;
  // w_end scaled so that g(A) falls by 1 per unit of v; false where g(A) hardly changes along it
  auto scaled = [&](Point3 w, Point3& out) {
    const Point3 slope_w = straight_slope(w);
    const double slope = dot(n_g, slope_w);
    if (!(slope < 0) || !(-slope > 1e-6 * std::sqrt(dot(n_g, n_g) * dot(slope_w, slope_w)))) return false;
    out = (-1 / slope) * w;
    return true;
  };
  Point3 w_end[2], w_across;
  if (!scaled(across, w_across)) return;
  for (int i = 0; i < 2; ++i)
    if (ends[i] == Point3() || !scaled(ends[i], w_end[i])) w_end[i] = w_across;
  const Point3 a_slope_d = straight_slope(face.d);  // dA/dl along the column
  // F2, the face beyond e in F's plane: its columns as F's, in its two tetrahedra (across -2: no such face)
  BandFace beyond = face;
  beyond.across = -2;
  int same = -1, other = -1;
  if (coplanar_beyond(kf, j, g_face, same, other)) set_face_tets(beyond, same, other);
  if (band_moments_) beyond_moments_.clear();
  // the column from xi0: its root l, and g at its end
  struct Column {
    Point3 xi, x, D[3], dd;
    double l;
  };
  // X, dX/dxi and dX/dl along the column at xi0: a quadratic map's by its Taylor terms about the last point the
  // map itself gave (base: each of the rule's points along the edge), X(b + r) = X(b) + D r + r^T H r / 2 and
  // dX/dxi_i(b + r) = D_i + (H r)_i
  double hessian[3][3][3];
  if (face.quadratic) image.tetrahedron.reference_hessian(hessian);
  Column base;
  bool based = false;
  auto evaluate = [&](Point3 xi0, Column& c) {
    c.xi = xi0;
    if (based) {
      const Point3 r = xi0 - base.xi;
      c.x = base.x;
      for (int i = 0; i < 3; ++i) {
        const Point3 hr = hessian_along(hessian, i, r);
        c.D[i] = base.D[i] + hr;
        c.x = c.x + coordinate(r, i) * (base.D[i] + 0.5 * hr);
      }
    } else {
      reference_value(image, xi0, c.x, c.D);
    }
    c.dd = face.d.x * c.D[0] + face.d.y * c.D[1] + face.d.z * c.D[2];
  };
  auto column = [&](Point3 xi0, Column& c) {
    evaluate(xi0, c);
    c.l = column_root(image, face, n, y_edge, xi0, c.x, c.dd, rise);
    return std::isfinite(c.l);
  };
  // X along the column: a quadratic map's Taylor terms (exact), else the map itself
  auto along_column = [&](const Column& c, double t) {
    return face.quadratic ? c.x + (t * c.dd + (0.5 * t * t) * face.dhd) : reference_position(image, c.xi + t * face.d);
  };
  auto end_g = [&](const Column& c) { return g(along_column(c, c.l)); };
  const LineRule& rule = line_rule(image.degree + 2);
  const int count = static_cast<int>(rule.nodes.size());
  for (int k = 0; k < count; ++k) {
    const Point3 xi_u = xi_a + rule.nodes[k] * along;
    const Point3 w = (1 - rule.nodes[k]) * w_end[0] + rule.nodes[k] * w_end[1], dw = w_end[1] - w_end[0];
    // v1: where the column's end crosses G, g(X(end)) = 0 (secant from v = 0, g(X(end)) falling about 1 per unit)
    Column c;
    based = false;
    if (!column(xi_u, c)) continue;
    if (face.quadratic) {
      base = c;
      based = true;
    }
    double v0 = 0, f0 = end_g(c), v1 = f0, f1 = 0;
    if (f0 == 0) continue;
    bool found = false;
    for (int it = 0; it < 30; ++it) {
      if (!column(xi_u + v1 * w, c)) break;
      f1 = end_g(c);
      if (f1 == 0 || std::fabs(v1 - v0) <= 1e-12) {
        found = true;
        break;
      }
      const double next = v1 - f1 * (v1 - v0) / (f1 - f0);
      if (!std::isfinite(next)) break;
      v0 = v1;
      f0 = f1;
      v1 = next;
    }
    // inside F (v1 > 0): J_F2 - J_F, or -J_F; beyond e: F2's own strip, or +J_F
    // A strip a sizeable part of the fluid tetrahedron wide (v in its barycentric units) is beyond the premise
    // of one edge crossed near e: left as the columns have it.
    if (!found || std::fabs(v1) > 0.25 || (v1 < 0 && beyond.across != -2)) continue;
    for (int q = 0; q < count; ++q) {
      const double v = rule.nodes[q] * v1;
      const Point3 xi0 = xi_u + v * w;
      if (!column(xi0, c) || c.l == 0) continue;
      const Point3 a0 = straight_position(image, xi0);
      // g(Y*(t)): a = rise t along the column, q = n . (X - y)
      auto h = [&](double t) {
        const Point3 x = along_column(c, t), a = a0 + t * a_slope_d;
        const double at = rise * t, qt = dot(n, x - y_edge);
        return (at * g(x) - qt * g(a)) / (at - qt);
      };
      const double h0 = g(a0), hl = end_g(c);
      if ((h0 < 0) == (hl < 0)) continue;
      const double tc = bracketed_root(h, c.l, h0, hl);
      Column from;
      evaluate(xi0 + tc * face.d, from);
      const double l = c.l - tc;
      // -J_F where the start is inside (v > 0), +J_F where it is outside: -sign(v) per unit of |v|
      // the start's area: |d xi0/du x d xi0/dv| = |(along + v dw) x w|
      const Point3 du = along + v * dw, normal = cross(du, w);
      const double area = std::sqrt(dot(normal, normal)) * solid_det;
      const double weight = -rule.weights[k] * rule.weights[q] * v1 * area * height * l;
      if (band_moments_)
        add_column_moments(face, from.xi, from.x, from.dd, l, weight);
      else
        add_column(image, kf, face, from.xi, from.x, from.dd, from.D, l, weight);
      if (beyond.across == -2) continue;
      if (band_moments_)
        add_column_moments(beyond, from.xi, from.x, from.dd, l, -weight, &beyond_moments_);
      else
        add_column(image, kf, beyond, from.xi, from.x, from.dd, from.D, l, -weight, same);
    }
  }
  if (!band_moments_ || beyond.across == -2) return;
  beyond_moments_.settle();
  if (beyond_moments_.points() == 0) return;
  add_face_moments(image, same, 1, &beyond_moments_);  // J_F2 = f_same - f_other
  if (other >= 0) add_face_moments(image, other, -1, &beyond_moments_);
}

}  // namespace dlmfsi
