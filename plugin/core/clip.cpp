#include "clip.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "predicates.hpp"

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

Piece clip(const Point a[3], const Point b[3]) {
  Piece out;
  // side_ab[j][i]: side of a[i] with respect to edge b[j] -> b[j+1]; side_ba[i][j] likewise.
  int side_ab[3][3], side_ba[3][3];
  for (int j = 0; j < 3; ++j) {
    bool separates = true;
    for (int i = 0; i < 3; ++i) {
      side_ab[j][i] = orient2d(b[j], b[(j + 1) % 3], a[i]);
      if (side_ab[j][i] > 0) separates = false;
    }
    if (separates) return out;
  }
  for (int i = 0; i < 3; ++i) {
    bool separates = true;
    for (int j = 0; j < 3; ++j) {
      side_ba[i][j] = orient2d(a[i], a[(i + 1) % 3], b[j]);
      if (side_ba[i][j] > 0) separates = false;
    }
    if (separates) return out;
  }

  Point cand[12];
  int n = 0;
  for (int i = 0; i < 3; ++i)
    if (side_ab[0][i] >= 0 && side_ab[1][i] >= 0 && side_ab[2][i] >= 0) cand[n++] = a[i];
  for (int j = 0; j < 3; ++j)
    if (side_ba[0][j] >= 0 && side_ba[1][j] >= 0 && side_ba[2][j] >= 0 && b[j] != a[0] && b[j] != a[1] &&
        b[j] != a[2])
      cand[n++] = b[j];
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      if (side_ab[j][i] * side_ab[j][i1] < 0 && side_ba[i][j] * side_ba[i][j1] < 0)
        cand[n++] = crossing(a[i], a[i1], b[j], b[j1]);
    }
  }
  if (n < 3) return out;  // cannot happen when the interiors meet; kept as a guard

  // The candidates are the vertices of a convex polygon: order them by angle about their mean c, with
  // exact comparisons. The directions seen from c are split into the half-turns [0, 180) and [180, 360)
  // degrees; within one, "q left of c -> p" is a strict weak order. Floating-point angles (the former
  // pseudo-angle keys) misordered thin pieces whose vertices lie nearly on one ray from c, giving pieces
  // that did not wind once; exact comparisons of the actual doubles cannot, while c is inside.
  Point c{0, 0};
  for (int k = 0; k < n; ++k) c = c + cand[k];
  c = (1.0 / n) * c;
  auto half = [c](Point p) {
    if (p == c) return 0;
    return p.y > c.y || (p.y == c.y && p.x > c.x) ? 1 : 2;
  };
  auto before = [c, &half](Point p, Point q) {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    if (hp == 0) return false;
    const int o = orient2d(c, p, q);
    return o > 0 || (o == 0 && lex_less(p, q));
  };
  for (int k = 1; k < n; ++k)
    for (int m = k; m > 0 && before(cand[m], cand[m - 1]); --m) std::swap(cand[m], cand[m - 1]);
  out.n = std::min(n, Piece::kMaxVertices);
  for (int k = 0; k < out.n; ++k) out.v[k] = cand[k];
  return out;
}

}  // namespace dlmfsi
