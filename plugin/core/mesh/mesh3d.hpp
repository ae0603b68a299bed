// A tetrahedral mesh as plain arrays, with face adjacency.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "point3.hpp"

namespace dlmfsi {

struct Mesh3 {
  std::vector<Point3> vertices;
  std::vector<std::array<int, 4>> tetrahedra;  // positively oriented: orient3d(v0, v1, v2, v3) > 0
  // neighbours[k][i]: the tetrahedron across the face opposite vertex i of tetrahedron k, or -1 on the
  // boundary.
  std::vector<std::array<int, 4>> neighbours;

  int size() const { return static_cast<int>(tetrahedra.size()); }
  Point3 vertex(int k, int i) const { return vertices[tetrahedra[k][i]]; }
  void corners(int k, Point3 out[4]) const {
    for (int i = 0; i < 4; ++i) out[i] = vertex(k, i);
  }

  // Throws Error for a non-finite vertex, a bad vertex index, or a tetrahedron that is not positively
  // oriented (checked with the exact predicate).
  void check() const;
  // check(), then fills neighbours; throws Error for a face shared by more than two tetrahedra.
  void build_adjacency();
};

// The tetrahedra sorted by the Morton code of their centroids (10 bits per coordinate of the bounding box,
// interleaved): neighbours in space come close in the order.
std::vector<int> morton_order(const Mesh3& mesh);

// The mesh with tetrahedron i = mesh's tetrahedron order[i] and the vertices numbered in the order the
// tetrahedra first use them (the same points and neighbours, laid out along the order for the caches).
Mesh3 renumbered(const Mesh3& mesh, const std::vector<int>& order);

// Point with reference coordinates xi in tetrahedron {p0, p1, p2, p3}: p0 + xi1 (p1 - p0) + xi2 (p2 - p0) +
// xi3 (p3 - p0) (FreeFEM's reference tetrahedron: (0,0,0), (1,0,0), (0,1,0), (0,0,1)).
inline Point3 from_reference(const Point3 p[4], Point3 xi) {
  return p[0] + xi.x * (p[1] - p[0]) + xi.y * (p[2] - p[0]) + xi.z * (p[3] - p[0]);
}

// The inverse of from_reference for a non-degenerate tetrahedron (Cramer's rule).
inline Point3 to_reference(const Point3 p[4], Point3 x) {
  const Point3 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0], d = x - p[0];
  const double det = dot(e1, cross(e2, e3));
  return {dot(d, cross(e2, e3)) / det, dot(e1, cross(d, e3)) / det, dot(e1, cross(e2, d)) / det};
}

// Does det = 6 |volume| of a tetrahedron lie within 2^-1000 .. 2^1000 (tetrahedra from about 1e-100 to 1e100 in
// size, whose volumes h^3 and their products with gradients 1/h stay normal numbers)?
inline bool supported_tetrahedron_size(double det) { return det >= 0x1p-1000 && det <= 0x1p1000; }
// Throws unless supported_tetrahedron_size(det); who names the tetrahedron ("fluid tetrahedron 3"), side its
// mesh ("fluid").
void check_tetrahedron_size(double det, const std::string& who, const char* side);
// The same for tetrahedron k of the side's mesh, named "<side> tetrahedron k" (the name made only for the error).
inline void check_tetrahedron_size(double det, int k, const char* side) {
  if (!supported_tetrahedron_size(det))
    check_tetrahedron_size(det, std::string(side) + " tetrahedron " + std::to_string(k), side);
}

}  // namespace dlmfsi
