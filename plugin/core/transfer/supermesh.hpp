// The supermesh of two triangle meshes: their common refinement over the region both cover.
#pragma once
#include <array>
#include <vector>

#include "mesh/mesh.hpp"

namespace dlmfsi {

struct Supermesh {
  std::vector<Point> vertices;                // shared by the pieces that meet there (exact coordinates)
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise, positive area in floating point
  // parent_a[t], parent_b[t]: the triangle of A and of B that triangle t lies in.
  std::vector<int> parent_a, parent_b;

  // An edge of the supermesh used by one triangle only: edge `edge` (opposite vertex `edge`) of
  // triangle `triangle`. side 0: it lies on edge `parent_edge` (opposite that vertex) of parent_a[triangle],
  // a boundary edge of A; side 1: the same on B; -1: on neither (an edge left open by a dropped sliver).
  struct BoundaryEdge {
    int triangle, edge, side, parent_edge;
  };
  std::vector<BoundaryEdge> boundary;

  long pieces = 0;           // non-empty intersections A_k ∩ B_l (convex polygons)
  double area = 0;           // sum of the triangles' areas
  int collapsed = 0;         // fan triangles with two corners merged into one vertex (removed)
  int dropped = 0;           // fan triangles with three vertices but flat or clockwise after merging (removed;
                             // each may leave a pair of open edges: boundary edges of side -1)
  double dropped_area = 0;   // the area of the collapsed and dropped triangles before merging (round-off size)
  int size() const { return static_cast<int>(triangles.size()); }
};

// The supermesh of a and b (both with adjacency built; b is searched with FluidSearch).
//
// Every non-empty intersection of a triangle of a with a triangle of b (a convex polygon of 3 to 6
// vertices, from clip()) is split into triangles by a fan from the vertex that gives the fan's largest
// smallest triangle. Vertices with bit-identical coordinates are merged: clip() gives the vertices of a and
// b exactly and every crossing of an edge of a with an edge of b with the same bits in all four pieces
// around it, so for conforming a and b the pieces meet edge to edge and the result is conforming.
// Points within 1e-12 of the overlap's diameter are merged too (an edge of one mesh that passes through a
// vertex of the other in real arithmetic, as grids of commensurate sizes do, leaves crossing points 1e-17
// from that vertex): the fan triangles that collapse are removed (`collapsed`), and the rare one that
// comes out flat or clockwise is dropped (`dropped`).
// Triangles are ordered by the triangle of a, then by the search order in b.
// Boundary edges are matched to the boundary edges of the parents geometrically: both ends within
// 1e-10 of the parent edge's length from its line.
Supermesh build_supermesh(const Mesh& a, const Mesh& b);

}  // namespace dlmfsi
