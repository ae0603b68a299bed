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
  t = std::min(1.0, std::max(0.0, t));
  return {p.x + t * d.x, p.y + t * d.y};
}

namespace {

// A monotone stand-in for the angle of d (in [0, 4)), cheaper than atan2.
double pseudo_angle(Point d) {
  const double s = std::fabs(d.x) + std::fabs(d.y);
  if (s == 0) return 0;
  const double p = d.x / s;  // in [-1, 1], decreasing with the angle on the upper half
  return d.y >= 0 ? 1 - p : 3 + p;
}

}  // namespace

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

  // The candidates are the vertices of a convex polygon: order them by angle about their mean.
  Point c{0, 0};
  for (int k = 0; k < n; ++k) c = c + cand[k];
  c = (1.0 / n) * c;
  double key[12];
  for (int k = 0; k < n; ++k) key[k] = pseudo_angle(cand[k] - c);
  for (int k = 1; k < n; ++k)
    for (int m = k; m > 0 && key[m] < key[m - 1]; --m) {
      std::swap(key[m], key[m - 1]);
      std::swap(cand[m], cand[m - 1]);
    }
  out.n = std::min(n, Piece::kMaxVertices);
  for (int k = 0; k < out.n; ++k) out.v[k] = cand[k];
  return out;
}

}  // namespace dlmfsi
