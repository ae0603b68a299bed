// A triangle mesh as plain arrays, with edge adjacency.
#pragma once
#include <array>
#include <vector>

#include "point.hpp"

namespace dlmfsi {

struct Mesh {
  std::vector<Point> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise vertex indices
  // neighbours[k][i]: the triangle across the edge opposite vertex i of triangle k, or -1 on the boundary.
  std::vector<std::array<int, 3>> neighbours;

  int size() const { return static_cast<int>(triangles.size()); }
  Point vertex(int k, int i) const { return vertices[triangles[k][i]]; }
  void corners(int k, Point out[3]) const {
    for (int i = 0; i < 3; ++i) out[i] = vertex(k, i);
  }

  // Throws Error for a non-finite vertex, a bad vertex index, or a triangle that is not of positive
  // orientation (checked with the exact predicate).
  void check() const;
  // check(), then fills neighbours; throws Error for an edge shared by more than two triangles.
  void build_adjacency();
};

// The triangles sorted by the Morton code of their centroids (16 bits per coordinate of the bounding box,
// interleaved): neighbours in the plane come close in the order.
std::vector<int> morton_order(const Mesh& mesh);

// The mesh with triangle i = mesh's triangle order[i] and the vertices numbered in the order the triangles
// first use them (the same points and neighbours, laid out along the order for the memory caches).
Mesh renumbered(const Mesh& mesh, const std::vector<int>& order);

// Point with barycentric-type reference coordinates (l1, l2) in triangle {p0, p1, p2}: p0 + l1 (p1 - p0) + l2 (p2 - p0).
inline Point from_reference(const Point p[3], Point xi) {
  return {p[0].x + xi.x * (p[1].x - p[0].x) + xi.y * (p[2].x - p[0].x),
          p[0].y + xi.x * (p[1].y - p[0].y) + xi.y * (p[2].y - p[0].y)};
}

// The inverse of from_reference for a non-degenerate triangle.
inline Point to_reference(const Point p[3], Point x) {
  const Point e1 = p[1] - p[0], e2 = p[2] - p[0], d = x - p[0];
  const double det = cross(e1, e2);
  return {cross(d, e2) / det, cross(e1, d) / det};
}

}  // namespace dlmfsi
