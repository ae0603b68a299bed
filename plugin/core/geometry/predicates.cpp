#include "geometry/predicates.hpp"

#include "geometry/exact_sign.hpp"

namespace dlmfsi {

int orient2d_exact(Point a, Point b, Point c) {
  const double f[6][2] = {{a.x, b.y}, {-a.y, b.x}, {b.x, c.y}, {-b.y, c.x}, {c.x, a.y}, {-c.y, a.x}};
  return exact_sign_of_sum(&f[0][0], 6, 2);
}

int cross_sign_exact(Point p, Point q, Point r, Point s) {
  // (q - p) x (s - r) = qx sy - qx ry - px sy + px ry - qy sx + qy rx + py sx - py rx
  const double f[8][2] = {{q.x, s.y}, {-q.x, r.y}, {-p.x, s.y}, {p.x, r.y},
                          {-q.y, s.x}, {q.y, r.x}, {p.y, s.x}, {-p.y, r.x}};
  return exact_sign_of_sum(&f[0][0], 8, 2);
}

ScaledValue orient2d_value(Point a, Point b, Point c) {
  // det [b - a, c - a] = ax by - ay bx + bx cy - by cx + cx ay - cy ax
  const double f[6][2] = {{a.x, b.y}, {-a.y, b.x}, {b.x, c.y}, {-b.y, c.x}, {c.x, a.y}, {-c.y, a.x}};
  ScaledValue v;
  v.m = exact_sum(&f[0][0], 6, 2, v.e);
  return v;
}

}  // namespace dlmfsi
