#include "geometry/clip.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/predicates.hpp"

namespace dlmfsi {

double Piece::area() const {
  double s = 0;
  for (int i = 1; i + 1 < n; ++i) s += area2(v[0], v[i], v[i + 1]);
  return 0.5 * s;
}

Point crossing(Point p, Point q, Point r, Point s) {
  if (lex_less(q, p)) std::swap(p, q);
  if (lex_less(s, r)) std::swap(r, s);
  if (lex_less(r, p) || (r == p && lex_less(s, q))) {
    std::swap(p, r);
    std::swap(q, s);
  }
  // p + t (q - p) with t = cross(r - p, s - r) / cross(q - p, s - r), clamped to the segment.
  const Point d = q - p, e = s - r;
  double t = cross(r - p, e) / cross(d, e);
  t = std::min(1.0, std::max(0.0, t));  // also maps NaN (parallel in floating point) to 0
  // The crossing lies on both segments, so in both bounding boxes. For nearly parallel, nearly collinear
  // segments t is ill-conditioned and p + t d can land anywhere on [p, q], far outside [r, s] (seen with
  // collinear overlapping edges perturbed by one rounding: a piece grew by 9% of its area); clamped to the
  // boxes' intersection the point stays in the overlap, within round-off of both lines.
  const double x = p.x + t * d.x, y = p.y + t * d.y;
  const double lx = std::max(std::min(p.x, q.x), std::min(r.x, s.x)), hx = std::min(std::max(p.x, q.x), std::max(r.x, s.x));
  const double ly = std::max(std::min(p.y, q.y), std::min(r.y, s.y)), hy = std::min(std::max(p.y, q.y), std::max(r.y, s.y));
  return {std::min(hx, std::max(lx, x)), std::min(hy, std::max(ly, y))};
}

namespace {

// side[j][i] = orient2d(e[j], e[j + 1], p[i]) for the nine pairs: orient2d's floating-point filter for all
// nine first (without a branch), then the exact evaluation for the undecided ones.
void filtered_sides(const Point e[3], const Point p[3], int side[3][3]) {
  bool undecided = false;
  for (int i = 0; i < 3; ++i) {
    // e's corners less p[i], each difference formed once for the two edges that share the corner: edge j's
    // products (u.x - p.x) (v.y - p.y) and (u.y - p.y) (v.x - p.x), u = e[j], v = e[j + 1], are orient2d's
    double dx[4], dy[4];
    for (int j = 0; j < 3; ++j) {
      dx[j] = e[j].x - p[i].x;
      dy[j] = e[j].y - p[i].y;
    }
    dx[3] = dx[0];
    dy[3] = dy[0];
    for (int j = 0; j < 3; ++j) {
      const int s = filtered_sign(dx[j] * dy[j + 1], dy[j] * dx[j + 1]);
      side[j][i] = s;
      undecided |= s == 0;
    }
  }
  if (!undecided) return;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      if (side[j][i] == 0) side[j][i] = orient2d_exact(e[j], e[(j + 1) % 3], p[i]);
}

// a reaches beyond one edge line j of b only: a ∩ b = a ∩ (closed side of line j). With no vertex of a on
// that line and b's edge crossing a's two cut edges properly (exact signs), the piece is a's vertices on
// the inner side and the two crossings, as polygon_of_corners would find them.
// Returns false, leaving out and rest alone, when a vertex of a lies on the line or a cut edge of a passes
// through a vertex of b: then polygon_of_corners decides.
bool cut_by_one_line(const Point a[3], const Point b[3], const int side_ab[3][3], int j, Piece& out, Rest& rest) {
  const int j1 = (j + 1) % 3;
  const int* side = side_ab[j];
  if (side[0] != 0 && side[1] != 0 && side[2] != 0) {
    // With a's vertices strictly inside the other two edges' lines, a cut edge of a stays strictly inside
    // them, so it meets line j strictly between b[j] and b[j1] (the line and those two open half-planes
    // meet in the open edge): a proper crossing, without asking. Otherwise ask (a cut edge through a
    // vertex of b).
    const int *other = side_ab[j1], *other2 = side_ab[(j + 2) % 3];
    bool proper = true;
    if (!(other[0] > 0 && other[1] > 0 && other[2] > 0 && other2[0] > 0 && other2[1] > 0 && other2[2] > 0))
      for (int i = 0; i < 3 && proper; ++i) {
        const int i1 = (i + 1) % 3;
        if (side[i] != side[i1])
          proper = orient2d(a[i], a[i1], b[j]) * orient2d(a[i], a[i1], b[j1]) < 0;
      }
    if (proper) {
      Piece& beyond_line = rest.piece;
      beyond_line.n = 0;
      rest.corners = 0;
      for (int i = 0; i < 3; ++i) {
        const int i1 = (i + 1) % 3;
        if (side[i] > 0) {
          out.v[out.n++] = a[i];
        } else {
          beyond_line.v[beyond_line.n++] = a[i];
          rest.corners |= 1u << i;
        }
        if (side[i] != side[i1]) {
          const Point x = crossing(a[i], a[i1], b[j], b[j1]);
          out.v[out.n++] = x;
          beyond_line.v[beyond_line.n++] = x;
        }
      }
      rest.edge = j;
      return true;
    }
  }
  return false;
}

// The convex polygon a ∩ b from the sides of each triangle's corners with respect to the other's edge lines,
// when neither holds the other and no edge line separates them.
void polygon_of_corners(const Point a[3], const Point b[3], const int side_ab[3][3], const int side_ba[3][3],
                        Piece& out) {
  // The candidates are the corners of the convex polygon a ∩ b. With each goes the input edge along which
  // the polygon's boundary leaves it counter-clockwise (from, to): the corners are then ordered by the
  // directions of those edges, which increase around a convex polygon. Both the edge choice and the order
  // are exact decisions on the input coordinates, so the order is right however the constructed crossings
  // are rounded. (Ordering by floating-point angles about the vertices' mean swapped crossings a few ulps
  // apart; even exact orientations of the rounded vertices about the mean misorder thin pieces, whose
  // vertices far apart along an edge lie within rounding of one ray from the mean.)
  // (A plain struct, not Point: Point's members are zero-initialized, and clearing these arrays on every
  // call was about a tenth of clip's time.)
  struct Candidate {
    double x, y;
    const Point *from, *to;
  };
  Candidate cand[12];
  int n = 0;
  auto add = [&](Point v, const Point& p, const Point& q) {
    cand[n] = {v.x, v.y, &p, &q};
    ++n;
  };
  for (int i = 0; i < 3; ++i) {
    if (side_ab[0][i] < 0 || side_ab[1][i] < 0 || side_ab[2][i] < 0) continue;
    // a[i] in closed b: the boundary leaves it along a's edge i, unless a[i] lies on b's boundary (on the
    // lines of b's edges with side 0) and a's edge i leaves b there; then along b's edge passing through
    // a[i] or starting at it (with two zero sides, of b's edges j - 1 and j, a[i] is b[j]: edge j).
    const int i1 = (i + 1) % 3;
    bool along_a = true;
    int jb = -1;
    for (int j = 0; j < 3; ++j)
      if (side_ab[j][i] == 0) {
        if (side_ab[j][i1] < 0) along_a = false;
        if (jb < 0 || side_ab[(j + 2) % 3][i] == 0) jb = j;
      }
    if (along_a) add(a[i], a[i], a[i1]);
    else add(a[i], b[jb], b[(jb + 1) % 3]);
  }
  for (int j = 0; j < 3; ++j) {
    if (side_ba[0][j] < 0 || side_ba[1][j] < 0 || side_ba[2][j] < 0 || b[j] == a[0] || b[j] == a[1] || b[j] == a[2])
      continue;
    // b[j] in closed a and not a vertex of a: on at most one of a's edge lines
    const int j1 = (j + 1) % 3;
    int ia = -1;
    for (int i = 0; i < 3; ++i)
      if (side_ba[i][j] == 0 && side_ba[i][j1] < 0) ia = i;
    if (ia < 0) add(b[j], b[j], b[j1]);
    else add(b[j], a[ia], a[(ia + 1) % 3]);
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      if (side_ab[j][i] * side_ab[j][i1] < 0 && side_ba[i][j] * side_ba[i][j1] < 0) {
        // a proper crossing: a's edge enters b here (then the boundary follows it) or leaves b (then b's edge
        // enters a and the boundary follows that)
        const Point x = crossing(a[i], a[i1], b[j], b[j1]);
        if (side_ab[j][i1] > 0) add(x, a[i], a[i1]);
        else add(x, b[j], b[j1]);
      }
    }
  }
  if (n < 3) return;  // cannot happen when the interiors meet; kept as a guard

  // Order by the direction to - from: the half-turn [0, 180) degrees first, then [180, 360); within one,
  // by the exact sign of the cross product of the two directions.
  auto half = [&](int k) {
    const Point &from = *cand[k].from, &to = *cand[k].to;
    return to.y > from.y || (to.y == from.y && to.x > from.x) ? 0 : 1;
  };
  auto before = [&](int k, int m) {
    const int hk = half(k), hm = half(m);
    if (hk != hm) return hk < hm;
    return cross_sign(*cand[k].from, *cand[k].to, *cand[m].from, *cand[m].to) > 0;
  };
  int order[12];
  for (int k = 0; k < n; ++k) order[k] = k;
  for (int k = 1; k < n; ++k)
    for (int m = k; m > 0 && before(order[m], order[m - 1]); --m) std::swap(order[m], order[m - 1]);
  out.n = std::min(n, Piece::kMaxVertices);
  for (int k = 0; k < out.n; ++k) out.v[k] = {cand[order[k]].x, cand[order[k]].y};
}

}  // namespace

Piece clip(const Point a[3], const Point b[3]) {
  unsigned beyond;
  return clip(a, b, beyond);
}

Piece clip(const Point a[3], const Point b[3], unsigned& beyond) {
  Rest rest;
  return clip(a, b, beyond, rest);
}

Piece clip(const Point a[3], const Point b[3], unsigned& beyond, Rest& rest) {
  Piece out;
  rest.edge = -1;
  beyond = 0;
  // side_ab[j][i]: side of a[i] with respect to edge b[j] -> b[j+1]; side_ba[i][j] likewise.
  int side_ab[3][3], side_ba[3][3];
  filtered_sides(b, a, side_ab);
  for (int j = 0; j < 3; ++j) {
    bool separates = true;
    for (int i = 0; i < 3; ++i) {
      if (side_ab[j][i] > 0) separates = false;
      if (side_ab[j][i] < 0) beyond |= 1u << j;
    }
    if (separates) return out;
  }
  // A whole triangle, from its lexicographically smallest vertex, so that the piece does not depend on
  // which vertex a triangle lists first.
  auto whole = [&out](const Point t[3]) {
    const int first = lex_less(t[1], t[0]) ? (lex_less(t[2], t[1]) ? 2 : 1) : (lex_less(t[2], t[0]) ? 2 : 0);
    out.n = 3;
    for (int k = 0; k < 3; ++k) out.v[k] = t[(first + k) % 3];
    return out;
  };
  if (beyond == 0) return whole(a);  // a in closed b
  const int only_line = beyond == 1 ? 0 : (beyond == 2 ? 1 : (beyond == 4 ? 2 : -1));  // beyond one line only
  if (only_line >= 0 && cut_by_one_line(a, b, side_ab, only_line, out, rest)) return out;
  bool b_inside = true;
  filtered_sides(a, b, side_ba);
  for (int i = 0; i < 3; ++i) {
    bool separates = true;
    for (int j = 0; j < 3; ++j) {
      if (side_ba[i][j] > 0) separates = false;
      if (side_ba[i][j] < 0) b_inside = false;
    }
    if (separates) return out;
  }
  if (b_inside) return whole(b);
  polygon_of_corners(a, b, side_ab, side_ba, out);
  return out;
}

}  // namespace dlmfsi
