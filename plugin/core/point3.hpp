// Points of space and the few vector operations the 3D core needs.
#pragma once

namespace dlmfsi {

struct Point3 {
  double x = 0, y = 0, z = 0;
};

inline Point3 operator+(Point3 a, Point3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Point3 operator-(Point3 a, Point3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Point3 operator*(double s, Point3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline bool operator==(Point3 a, Point3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline bool operator!=(Point3 a, Point3 b) { return !(a == b); }
// Coordinate a (0: x, 1: y, 2: z) of p.
inline double coordinate(Point3 p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }
inline double dot(Point3 a, Point3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Point3 cross(Point3 a, Point3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// Six times the signed volume of (a, b, c, d), det [b - a, c - a, d - a], in floating point (not a predicate).
inline double volume6(Point3 a, Point3 b, Point3 c, Point3 d) { return dot(b - a, cross(c - a, d - a)); }

// Lexicographic order, used to make constructions independent of argument order.
inline bool lex_less(Point3 a, Point3 b) {
  return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}

}  // namespace dlmfsi
