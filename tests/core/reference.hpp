// Independent references for the clipper tests: exact areas (CGAL's exact kernel / GMP rationals) and a
// long-double Sutherland-Hodgman clipper. Nothing here uses the core's predicates or constructions, so a
// bug there cannot hide in the reference. (piece_check.hpp, included: the checks of a piece's shape,
// which do use the core's orient2d.)
#pragma once
#include "geometry/clip.hpp"
#include "piece_check.hpp"
#include "point.hpp"

namespace dlmfsi::ref {

// True when the exact reference (CGAL) was compiled in; without it exact_intersection_area() is the
// long-double clipper.
bool have_exact();

// Area of the intersection of the closed triangles a and b (either orientation), computed exactly with
// CGAL's Exact_predicates_exact_constructions_kernel and rounded once to double.
double exact_intersection_area(const Point a[3], const Point b[3]);

// Signed area of triangle t (positive counter-clockwise), exact (GMP rationals) and rounded once.
double exact_triangle_area(const Point t[3]);

// Sign of det [b - a, c - a] in GMP rationals (any finite doubles).
int exact_orientation(Point a, Point b, Point c);

// Exact sum of doubles, rounded once (GMP rationals): sums of piece areas without summation error, so
// that a measured error belongs to the pieces, not to the test's own additions.
class ExactSum {
 public:
  ExactSum();
  ~ExactSum();
  ExactSum(const ExactSum&) = delete;
  ExactSum& operator=(const ExactSum&) = delete;
  void add(double v);
  double value() const;

 private:
  struct Impl;
  Impl* impl_;
};

// Sutherland-Hodgman in long double (64-bit mantissa): an independent clipper for generic pairs (no
// vertex on an edge line of the other triangle), where its round-off is far below the tolerance.
long double sutherland_hodgman_area(const Point a[3], const Point b[3]);

}  // namespace dlmfsi::ref
