// The piece shared by two triangles: a convex polygon of at most 6 vertices.
#pragma once
#include <cmath>

#include "point.hpp"
#include "geometry/exact_sign.hpp"

namespace dlmfsi {

struct Piece {
  static constexpr int kMaxVertices = 6;
  // v[0 .. n): the vertices. A member of an anonymous union, which the constructor leaves uninitialized (a
  // Point is zero-initialized: clearing 96 bytes for every pair clipped, most of them never read).
  union {
    Point v[kMaxVertices];
  };
  Piece() {}
  int n = 0;           // number of vertices, counter-clockwise; 0 when the interiors do not meet
  double area() const;  // shoelace formula, >= 0 up to round-off
};

// Intersection of the closed counter-clockwise triangles a and b (both of positive orientation).
//
// Every decision is an exact orient2d sign on the input coordinates, so two fluid triangles that share an
// edge split a solid triangle consistently, and the pieces tile it:
//  - the interiors meet iff no edge line of a or b has the other triangle on its closed outer side
//    (separating-axis theorem for convex polygons); otherwise n = 0 (touching at a vertex or along an
//    edge is empty);
//  - the vertices are the vertices of a inside closed b, the vertices of b inside closed a (one copy of a
//    vertex shared by both), and the proper crossings of an edge of a with an edge of b;
//  - a crossing point is computed from the two segments in a canonical order (each segment's endpoints
//    sorted lexicographically, then the two segments), so every triangle that has those two segments as
//    edges gets bit-identical coordinates.
// Degenerate cases handled by name: shared edge (either orientation), vertex on an edge, vertex on a
// vertex, collinear overlapping edges, one triangle inside the other, identical triangles.
Piece clip(const Point a[3], const Point b[3]);

// The same, also telling across which edges of b the triangle a reaches: bit j of beyond is set when a
// vertex of a lies strictly outside the line of b's edge j (b[j] -> b[j+1]). Only there can a's interior
// meet a triangle on the other side of that edge, so a search over b's neighbours follows these edges only.
// Set whenever the piece is not empty. When a lies in closed b (beyond == 0) the piece is a itself, and
// when b lies in closed a it is b: both without constructing a point.
Piece clip(const Point a[3], const Point b[3], unsigned& beyond);

// What clip tells of the rest of a when it finds a ∩ b = a ∩ (inner side of the line of b's edge j): a
// reaches beyond that line only, with no vertex of a on it, and b's edge crosses a's two cut edges properly.
// The rest, a ∩ (outer side), is then a's vertices beyond the line and the same two crossings (bit for bit:
// crossing is canonical), counter-clockwise; edge = -1 when clip found a ∩ b otherwise.
struct Rest {
  int edge = -1;
  unsigned corners = 0;  // bit i: vertex i of a lies beyond the line
  Piece piece;
};
Piece clip(const Point a[3], const Point b[3], unsigned& beyond, Rest& rest);

// out = t - o for the n points of t when every coordinate's subtraction is exact (its TwoSum error term is
// zero); false otherwise (out is then not to be used). An exact translation changes no orient2d sign and no
// lexicographic order, so clip decides everything on translated triangles as on the originals, and its
// pieces are the originals' translated exactly, except that crossings are constructed from the translated
// coordinates: rounded to the ulp of the local coordinates rather than of |t|.
inline bool translate_exactly(const Point* t, int n, Point o, Point* out) {
  bool exact = true;
  for (int i = 0; i < n; ++i) {
    exact = exact_difference(t[i].x, o.x, out[i].x) && exact;
    exact = exact_difference(t[i].y, o.y, out[i].y) && exact;
  }
  return exact;
}

// The point where segments [p, q] and [r, s] cross (they must cross properly), canonical in the order of
// the four arguments and of the two segments.
Point crossing(Point p, Point q, Point r, Point s);

}  // namespace dlmfsi
