// Plane points and the few vector operations the core needs.
#pragma once

namespace dlmfsi {

struct Point {
  double x = 0, y = 0;
};

inline Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
inline Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
inline Point operator*(double s, Point a) { return {s * a.x, s * a.y}; }
inline bool operator==(Point a, Point b) { return a.x == b.x && a.y == b.y; }
inline bool operator!=(Point a, Point b) { return !(a == b); }
inline double cross(Point a, Point b) { return a.x * b.y - a.y * b.x; }

// Twice the signed area of (a, b, c), in floating point (not a predicate).
inline double area2(Point a, Point b, Point c) { return cross(b - a, c - a); }

// Lexicographic order, used to make constructions independent of argument order.
inline bool lex_less(Point a, Point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

}  // namespace dlmfsi
