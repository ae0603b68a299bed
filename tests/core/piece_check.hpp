// The output contract of clip() checked on one piece (header-only, no exact arithmetic beyond orient2d:
// shared by the unit tests and the libFuzzer target).
#pragma once
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "geometry/clip.hpp"
#include "point.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi::ref {

// The output contract of clip() for one piece: 0 or 3..6 finite vertices, convex and counter-clockwise
// up to the rounding of constructed vertices:
//  (a) every vertex w lies left of every edge line (v_k, v_k+1), or right of it by at most the effect of
//      moving the three points by turn_tol * M (M the coordinate scale):
//        -(e_k x (w - v_k)) <= turn_tol * M * (|e_k| + 2 |w - v_k|),  e_k = v_k+1 - v_k;
//  (b) the shoelace area in the given order equals the area of the vertices' convex hull, up to
//      turn_tol * M * (hull perimeter): the order goes once around the hull, counter-clockwise (a
//      misordered piece crosses itself and loses area, one that goes around twice doubles it).
// Slivers and needles narrower than the rounding pass, whatever the order of their rounded vertices.
struct PieceCheck {
  std::string error;            // "" or the first violation
  double worst_right = 0;       // largest -(e x (w - v)) / (M (|e| + 2 |w - v|)) over edges and vertices
  int exact_right_turns = 0;    // (edge, vertex) pairs the exact predicate calls right (allowed up to turn_tol)
  int repeated_vertices = 0;    // consecutive vertices that are the same double point
};

inline PieceCheck check_piece(const Piece& p, double M, double turn_tol) {
  PieceCheck c;
  if (p.n == 0) return c;
  if (p.n < 3 || p.n > Piece::kMaxVertices) {
    c.error = "piece with " + std::to_string(p.n) + " vertices";
    return c;
  }
  for (int i = 0; i < p.n; ++i)
    if (!std::isfinite(p.v[i].x) || !std::isfinite(p.v[i].y)) {
      c.error = "vertex " + std::to_string(i) + " is not finite";
      return c;
    }
  const int n = p.n;
  for (int i = 0; i < n; ++i)
    if (p.v[i] == p.v[(i + 1) % n]) ++c.repeated_vertices;
  // (a) every vertex left of every edge line, up to rounding
  for (int k = 0; k < n; ++k) {
    const Point a = p.v[k], b = p.v[(k + 1) % n];
    if (a == b) continue;
    for (int m = 0; m < n; ++m) {
      const Point w = p.v[m];
      if (orient2d(a, b, w) >= 0) continue;
      ++c.exact_right_turns;
      const long double ex = static_cast<long double>(b.x) - a.x, ey = static_cast<long double>(b.y) - a.y;
      const long double wx = static_cast<long double>(w.x) - a.x, wy = static_cast<long double>(w.y) - a.y;
      const long double rel = -(ex * wy - ey * wx) / (M * (std::hypot(ex, ey) + 2 * std::hypot(wx, wy)));
      c.worst_right = std::max(c.worst_right, static_cast<double>(rel));
      if (rel > turn_tol && c.error.empty()) {
        std::ostringstream err;
        err << "vertex " << m << " right of edge " << k << " by " << static_cast<double>(rel) << " M (|e| + 2 |w - v|)";
        c.error = err.str();
      }
    }
  }
  // (b) once around the convex hull, counter-clockwise
  Point s[Piece::kMaxVertices], hull[2 * Piece::kMaxVertices];
  for (int i = 0; i < n; ++i) {  // insertion sort, lexicographic
    int k = i;
    for (; k > 0 && lex_less(p.v[i], s[k - 1]); --k) s[k] = s[k - 1];
    s[k] = p.v[i];
  }
  int h = 0;
  for (int i = 0; i < n; ++i) {  // lower hull
    while (h >= 2 && orient2d(hull[h - 2], hull[h - 1], s[i]) <= 0) --h;
    hull[h++] = s[i];
  }
  for (int i = n - 2, lower = h + 1; i >= 0; --i) {  // upper hull
    while (h >= lower && orient2d(hull[h - 2], hull[h - 1], s[i]) <= 0) --h;
    hull[h++] = s[i];
  }
  --h;  // the first point is repeated at the end
  long double hull_area = 0, area = 0;
  double hull_perimeter = 0;
  for (int i = 0; i < h; ++i) {
    const Point a = hull[i], b = hull[(i + 1) % h];
    hull_area += (static_cast<long double>(a.x) - hull[0].x) * (static_cast<long double>(b.y) - hull[0].y) -
                 (static_cast<long double>(a.y) - hull[0].y) * (static_cast<long double>(b.x) - hull[0].x);
    hull_perimeter += std::hypot(b.x - a.x, b.y - a.y);
  }
  for (int i = 0; i < n; ++i) {
    const Point a = p.v[i], b = p.v[(i + 1) % n];
    area += (static_cast<long double>(a.x) - p.v[0].x) * (static_cast<long double>(b.y) - p.v[0].y) -
            (static_cast<long double>(a.y) - p.v[0].y) * (static_cast<long double>(b.x) - p.v[0].x);
  }
  // (in long double: for pieces of subnormal size the tolerance underflows in double)
  if (std::fabs(area - hull_area) / 2 > static_cast<long double>(turn_tol) * M * hull_perimeter && c.error.empty()) {
    std::ostringstream err;
    err << "area " << static_cast<double>(area / 2) << " in the given order, " << static_cast<double>(hull_area / 2)
        << " for the convex hull";
    c.error = err.str();
  }
  return c;
}

// Largest |coordinate| of the six points, and the diameter of their bounding box.
inline double max_abs_coordinate(const Point a[3], const Point b[3]) {
  double m = 0;
  for (int i = 0; i < 3; ++i)
    m = std::max({m, std::fabs(a[i].x), std::fabs(a[i].y), std::fabs(b[i].x), std::fabs(b[i].y)});
  return m;
}

inline double box_diameter(const Point a[3], const Point b[3]) {
  double lx = a[0].x, hx = a[0].x, ly = a[0].y, hy = a[0].y;
  for (int i = 0; i < 3; ++i)
    for (Point p : {a[i], b[i]}) {
      lx = std::min(lx, p.x);
      hx = std::max(hx, p.x);
      ly = std::min(ly, p.y);
      hy = std::max(hy, p.y);
    }
  return std::hypot(hx - lx, hy - ly);
}

}  // namespace dlmfsi::ref
