// Which fluid triangles does a mapped solid triangle meet?
#pragma once
#include "geometry/clip.hpp"
#include "mesh/fluid_search_of.hpp"
#include "mesh/mesh.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

// The triangle meshes for FluidGridOf and FluidSearchOf.
struct Triangles {
  using Mesh = dlmfsi::Mesh;
  using Point = dlmfsi::Point;
  using Piece = dlmfsi::Piece;
  static constexpr int kDim = 2, kCorners = 3;
  // A clip costs about a location: the search clips t against the hint first (FluidSearchOf).
  static constexpr bool kClipHintFirst = true;

  static double coordinate(Point p, int a) { return a == 0 ? p.x : p.y; }
  // The grid's cells per axis for nt triangles over a box of widths w.
  static void cells_per_axis(int nt, const double w[2], int n[2]);
  // The bound on a visibility walk's steps in a mesh of n triangles.
  static int max_walk_steps(int n);

  static Point centroid(const Point t[3]) {
    return {(t[0].x + t[1].x + t[2].x) / 3, (t[0].y + t[1].y + t[2].y) / 3};
  }
  // The side of p with respect to the edge of triangle k opposite vertex i.
  static int side(const Mesh& m, int k, int i, Point p) {
    return orient2d(m.vertex(k, (i + 1) % 3), m.vertex(k, (i + 2) % 3), p);
  }
  // out = t - o when exact (translate_exactly in clip.hpp), for the search's pieces in local coordinates.
  static bool translate(const Point t[3], Point o, Point out[3]) { return translate_exactly(t, 3, o, out); }
  struct Faces {  // clip forms nothing ahead for a triangle
    void set(const Point*) {}
  };
  static Piece clip(const Point t[3], const Faces&, const Point k[3], unsigned& beyond) {
    return dlmfsi::clip(t, k, beyond);
  }
  using Rest = dlmfsi::Rest;
  static Piece clip(const Point t[3], const Faces&, const Point k[3], unsigned& beyond, Rest& rest) {
    return dlmfsi::clip(t, k, beyond, rest);
  }
  // The facet (opposite vertex i) of the rest's edge, or -1; the rest; t's corners in it.
  static int rest_facet(const Rest& r) { return r.edge < 0 ? -1 : (r.edge + 2) % 3; }
  static const Piece* rest_piece(const Rest& r) { return &r.piece; }
  static unsigned rest_corners(const Rest& r) { return r.corners; }
  // The edge opposite vertex i is clip's edge i + 1.
  static bool reaches_beyond(const Piece&, unsigned beyond, int i) { return beyond & (1u << ((i + 1) % 3)); }
};

// A uniform bucket grid over the fluid triangles' bounding boxes.
using FluidGrid = FluidGridOf<Triangles>;
// Point location and the pieces of a solid triangle over the fluid triangles.
using FluidSearch = FluidSearchOf<Triangles>;
extern template class FluidGridOf<Triangles>;
extern template class FluidSearchOf<Triangles>;

}  // namespace dlmfsi
