// The edges of a solid triangle's image under a fitted polynomial map, as polynomials of the edge's
// parameter, and a box that holds the whole image.
#pragma once
#include "map/element_map.hpp"

namespace dlmfsi {

struct ImageEdges {
  int degree = 0;  // the map's
  // Edge i runs from reference corner i to corner i + 1 of (0, 0), (1, 0), (0, 1): xi(t) = start(i) + t
  // direction(i), t in [0, 1], and X(xi(t)) - origin = sum_k coefficient[i][k] t^k (origin: the map's).
  Point coefficient[3][kMaxPolynomialMapDegree + 1];
  // The same edges' Bernstein control points on [0, 1] (relative to origin): each edge lies in their convex
  // hull, so a line with all of an edge's control points strictly on one side does not meet it.
  Point control[3][kMaxPolynomialMapDegree + 1];
  // The box of each edge's control points, which holds the edge's image.
  Point edge_lo[3], edge_hi[3];
  // X(T) - origin lies in [lo, hi]: the box of the map's Bernstein coefficients on T, whose convex hull
  // holds the image.
  Point lo, hi;

  // From the fitted map (map.fitted()).
  void set(const TriangleMap& map);

  static Point start(int i) { return i == 0 ? Point{0, 0} : i == 1 ? Point{1, 0} : Point{0, 1}; }
  static Point direction(int i) { return i == 0 ? Point{1, 0} : i == 1 ? Point{-1, 1} : Point{0, -1}; }
  // X(xi(t)) - origin on edge i.
  Point at(int i, double t) const {
    Point v = coefficient[i][degree];
    for (int k = degree - 1; k >= 0; --k) v = t * v + coefficient[i][k];
    return v;
  }
  // dX/dt on edge i.
  Point tangent(int i, double t) const {
    Point v{0, 0};
    for (int k = degree; k >= 1; --k) v = t * v + static_cast<double>(k) * coefficient[i][k];
    return v;
  }
};

}  // namespace dlmfsi
