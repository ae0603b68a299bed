// Which fluid tetrahedra does a mapped solid tetrahedron meet?
#pragma once
#include "geometry/clip3d.hpp"
#include "mesh/fluid_search_of.hpp"
#include "mesh/mesh3d.hpp"
#include "geometry/predicates3d.hpp"

namespace dlmfsi {

// The tetrahedral meshes for FluidGridOf and FluidSearchOf.
struct Tetrahedra {
  using Mesh = Mesh3;
  using Point = Point3;
  using Piece = Piece3;
  static constexpr int kDim = 3, kCorners = 4;
  // A clip costs several locations here: the search locates t's centroid first (FluidSearchOf).
  static constexpr bool kClipHintFirst = false;

  static double coordinate(Point3 p, int a) { return dlmfsi::coordinate(p, a); }
  // The grid's cells per axis for nt tetrahedra over a box of widths w.
  static void cells_per_axis(int nt, const double w[3], int n[3]);
  // The bound on a visibility walk's steps in a mesh of n tetrahedra.
  static int max_walk_steps(int n);

  static Point3 centroid(const Point3 t[4]) { return 0.25 * (t[0] + t[1] + t[2] + t[3]); }
  // The side of p with respect to the face of tetrahedron k opposite vertex i.
  static int side(const Mesh3& m, int k, int i, Point3 p) {
    Point3 c[4];
    m.corners(k, c);
    c[i] = p;
    return orient3d(c[0], c[1], c[2], c[3]);
  }
  // The same with k's face normals kept (element_planes): the floating-point filter on them first (face i's
  // plane is TetFaces' face i, whose sign is this orientation's), the exact orientation when it cannot decide.
  static int side(const Mesh3& m, int k, int i, Point3 p, const TetNormals& planes) {
    PlaneSide face;
    face.p = m.vertex(k, i == 0 ? 1 : 0);
    face.n = planes.n(i);
    face.pn = planes.pn(i);
    const int s = face.filter(p);
    return s != 0 ? s : side(m, k, i, p);
  }
  // out = t - o when exact (translate_exactly in clip3d.hpp), for the search's pieces in local coordinates.
  static bool translate(const Point3 t[4], Point3 o, Point3 out[4]) { return translate_exactly(t, 4, o, out); }
  // What clip keeps of t for all the fluid tetrahedra it meets: its face planes, and the crossings found so
  // far (neighbours share edges and faces, hence crossings), made for each t (set).
  struct Faces {
    TetFaces planes;
    mutable ClipMemo3 memo;
    void set(const Point3 t[4]) {
      planes.set(t);
      memo.clear();
    }
  };
  static Piece3 clip(const Point3 t[4], const Faces& faces, const Point3 k[4], unsigned& beyond) {
    return dlmfsi::clip_filtered(t, faces.planes, k, beyond, &faces.memo);
  }
  // What clip keeps of each fluid tetrahedron for every t (FluidSearchOf forms them once per mesh, for the
  // tetrahedra it meets): its face planes' normals.
  using ElementPlanes = TetNormals;
  static void element_planes(const Mesh3& m, int k, TetNormals& out) {
    Point3 c[4];
    m.corners(k, c);
    out.set(c);
  }
  static Piece3 clip(const Point3 t[4], const Faces& faces, const Point3 k[4], const TetNormals& k_planes,
                     unsigned& beyond) {
    return dlmfsi::clip_filtered(t, faces.planes, k, k_planes, beyond, &faces.memo);
  }
  struct Rest {};  // the clipper tells nothing of t beyond a face
  static Piece3 clip(const Point3 t[4], const Faces& faces, const Point3 k[4], unsigned& beyond, Rest&) {
    return dlmfsi::clip_filtered(t, faces.planes, k, beyond, &faces.memo);
  }
  static int rest_facet(const Rest&) { return -1; }
  static const Piece3* rest_piece(const Rest&) { return nullptr; }
  static unsigned rest_corners(const Rest&) { return 0; }
  // t reaches beyond face i's plane and the piece has a face on it: three or more of its vertices lie on that
  // plane (the vertices of a convex polytope on one of its supporting planes are one of its faces', and no three
  // of them are collinear). Where t reaches beyond the plane but the piece only touches it, or misses it, the
  // neighbour's piece is empty or met across another face (t's interior less the fluid edges is connected).
  static bool reaches_beyond(const Piece3& piece, unsigned beyond, int i) {
    if (!(beyond & (1u << i))) return false;
    int on = 0;
    for (int v = 0; v < piece.n; ++v) on += piece.planes[v] >> (4 + i) & 1;
    return on >= 3;
  }
};

// A uniform bucket grid over the fluid tetrahedra's bounding boxes.
using FluidGrid3 = FluidGridOf<Tetrahedra>;
// Point location and the pieces of a solid tetrahedron over the fluid tetrahedra.
using FluidSearch3 = FluidSearchOf<Tetrahedra>;
extern template class FluidGridOf<Tetrahedra>;
extern template class FluidSearchOf<Tetrahedra>;

}  // namespace dlmfsi
