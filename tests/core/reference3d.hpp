// Independent references for the 3D tests: exact signs and volumes in GMP rationals, and the exact volume
// of the intersection of two tetrahedra (CGAL's exact kernel when present, else GMP rationals through an
// independent half-space clipper). Nothing here uses the core's predicates or constructions.
#pragma once
#include "point3.hpp"

namespace dlmfsi::ref {

// Sign of det [b - a, c - a, d - a] in GMP rationals (any finite doubles).
int exact_orientation3d(Point3 a, Point3 b, Point3 c, Point3 d);

// det [b - a, c - a, d - a] in GMP rationals as m 2^e (m = 0, or 0.5 <= |m| < 1, truncated to a double):
// its value however far below the doubles it lies.
double exact_orientation3d_value(Point3 a, Point3 b, Point3 c, Point3 d, int& e);

// Signed volume of (a, b, c, d), exact and rounded once.
double exact_tet_volume(Point3 a, Point3 b, Point3 c, Point3 d);

// Volume of the intersection of the closed tetrahedra a and b (either orientation), computed exactly:
// a is clipped by the four half-spaces of b in rational arithmetic (each face a polygon of exact
// rational points), and the volume of the exact polyhedron is rounded once to double.
// When positive is given, it tells whether the exact volume is positive (its rounding may underflow to 0).
double exact_intersection_volume(const Point3 a[4], const Point3 b[4], bool* positive = nullptr);

}  // namespace dlmfsi::ref
