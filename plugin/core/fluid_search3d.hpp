// Which fluid tetrahedra does a mapped solid tetrahedron meet?
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "clip3d.hpp"
#include "mesh3d.hpp"

namespace dlmfsi {

// A uniform bucket grid over the fluid tetrahedra's bounding boxes (about one tetrahedron per cell): the
// fallback for point location and for tetrahedra whose search cannot start from an interior point.
class FluidGrid3 {
 public:
  explicit FluidGrid3(const Mesh3& fluid);
  const Mesh3& fluid() const { return fluid_; }
  // Calls f(k) for every fluid tetrahedron whose bounding box meets the box [lo, hi] (with repetitions).
  template <class F>
  void for_each_in_box(Point3 lo, Point3 hi, F&& f) const {
    int i0[3], i1[3];
    if (!cells_of(lo, hi, i0, i1)) return;
    for (int k = i0[2]; k <= i1[2]; ++k)
      for (int j = i0[1]; j <= i1[1]; ++j)
        for (int i = i0[0]; i <= i1[0]; ++i) {
          const size_t c = (static_cast<size_t>(k) * n_[1] + j) * n_[0] + i;
          for (int s = start_[c]; s < start_[c + 1]; ++s) f(items_[s]);
        }
  }

 private:
  bool cells_of(Point3 lo, Point3 hi, int* i0, int* i1) const;
  const Mesh3& fluid_;
  double lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0}, inv_[3] = {0, 0, 0};
  int n_[3] = {1, 1, 1};
  std::vector<int> start_, items_;
};

// Point location and piece enumeration; one per thread (it keeps visit marks).
class FluidSearch3 {
 public:
  explicit FluidSearch3(const FluidGrid3& grid);

  // A fluid tetrahedron whose closed set contains p, by a visibility walk from hint (>= 0) with exact
  // predicates, falling back to the grid; -1 when p lies outside the fluid mesh.
  int locate(Point3 p, int hint) const;

  // Calls visit(k, piece) once for every fluid tetrahedron k whose interior meets the interior of the
  // positively oriented tetrahedron t, with piece = t ∩ k. Advancing front: from the tetrahedron holding
  // t's centroid, across fluid faces while pieces are non-empty (the tetrahedra meeting a convex set are
  // face-connected through such tetrahedra, and a path inside t crosses each face where t reaches beyond
  // its plane); the grid when the centroid is outside the fluid mesh, and after the walk when t reaches
  // beyond a boundary face of a visited tetrahedron (t may re-enter a non-convex mesh).
  // hint: where the walk starts, updated to a tetrahedron near t.
  template <class Visit>
  void for_each_piece(const Point3 t[4], int& hint, Visit&& visit);

 private:
  bool mark(int k) {
    if (stamp_of_[k] == stamp_) return false;
    stamp_of_[k] = stamp_;
    return true;
  }
  const FluidGrid3& grid_;
  const Mesh3& fluid_;
  std::vector<unsigned> stamp_of_;
  unsigned stamp_ = 0;
  std::vector<int> queue_;
};

template <class Visit>
void FluidSearch3::for_each_piece(const Point3 t[4], int& hint, Visit&& visit) {
  if (++stamp_ == 0) {  // wrapped: clear the marks
    std::fill(stamp_of_.begin(), stamp_of_.end(), 0u);
    stamp_ = 1;
  }
  const Point3 centroid = 0.25 * (t[0] + t[1] + t[2] + t[3]);
  const int start = locate(centroid, hint);
  TetFaces t_faces;  // t's planes, formed once for all the fluid tetrahedra it is clipped against
  t_faces.set(t);
  Point3 k_corners[4];
  unsigned beyond;
  if (start >= 0) {
    fluid_.corners(start, k_corners);
    Piece3 first = clip(t, t_faces, k_corners, beyond);
    if (first.n > 0) {
      hint = start;
      queue_.clear();
      queue_.push_back(start);
      mark(start);
      bool at_boundary = false;
      for (std::size_t q = 0; q < queue_.size(); ++q) {
        const int k = queue_[q];
        if (q > 0) {
          fluid_.corners(k, k_corners);
          const Piece3 piece = clip(t, t_faces, k_corners, beyond);
          if (piece.n == 0) continue;
          visit(k, piece);
        } else {
          visit(k, first);
        }
        // Across face i only where t reaches beyond its plane.
        for (int i = 0; i < 4; ++i) {
          if (!(beyond & (1u << i))) continue;
          const int nb = fluid_.neighbours[k][i];
          if (nb < 0) at_boundary = true;
          else if (mark(nb)) queue_.push_back(nb);
        }
      }
      // The walk reached every piece unless t leaves the fluid mesh across a boundary face of a visited
      // tetrahedron: on a non-convex mesh t may come back in elsewhere. The grid finds the other parts
      // (the marks skip what the walk tested).
      if (!at_boundary) return;
    }
  }
  Point3 lo = t[0], hi = t[0];
  for (int i = 1; i < 4; ++i) {
    lo = {std::min(lo.x, t[i].x), std::min(lo.y, t[i].y), std::min(lo.z, t[i].z)};
    hi = {std::max(hi.x, t[i].x), std::max(hi.y, t[i].y), std::max(hi.z, t[i].z)};
  }
  grid_.for_each_in_box(lo, hi, [&](int k) {
    if (!mark(k)) return;
    fluid_.corners(k, k_corners);
    const Piece3 piece = clip(t, t_faces, k_corners, beyond);
    if (piece.n > 0) {
      hint = k;
      visit(k, piece);
    }
  });
}

}  // namespace dlmfsi
