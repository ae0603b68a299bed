// Which fluid triangles does a mapped solid triangle meet?
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "clip.hpp"
#include "mesh.hpp"

namespace dlmfsi {

// A uniform bucket grid over the fluid triangles' bounding boxes (about one triangle per cell):
// the fallback for point location and for triangles whose search cannot start from an interior point.
class FluidGrid {
 public:
  explicit FluidGrid(const Mesh& fluid);
  const Mesh& fluid() const { return fluid_; }
  // Calls f(k) for every fluid triangle whose bounding box meets the box [lo, hi] (with repetitions).
  template <class F>
  void for_each_in_box(Point lo, Point hi, F&& f) const {
    int i0, j0, i1, j1;
    if (!cells_of(lo, hi, i0, j0, i1, j1)) return;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const int c = j * nx_ + i;
        for (int s = start_[c]; s < start_[c + 1]; ++s) f(items_[s]);
      }
  }

 private:
  bool cells_of(Point lo, Point hi, int& i0, int& j0, int& i1, int& j1) const;
  const Mesh& fluid_;
  Point lo_, hi_;
  int nx_ = 1, ny_ = 1;
  double inv_dx_ = 0, inv_dy_ = 0;
  std::vector<int> start_, items_;
};

// Point location and piece enumeration; one per thread (it keeps visit marks).
class FluidSearch {
 public:
  explicit FluidSearch(const FluidGrid& grid);

  // A fluid triangle whose closed set contains p, by a visibility walk from hint (>= 0) with exact
  // predicates, falling back to the grid; -1 when p lies outside the fluid mesh.
  int locate(Point p, int hint) const;

  // Calls visit(k, piece) once for every fluid triangle k whose interior meets the interior of the
  // counter-clockwise triangle t, with piece = t ∩ k. Advancing front: from the triangle holding t's
  // centroid, across fluid edges while pieces are non-empty (the triangles meeting a convex set are
  // edge-connected through such triangles, and a path inside t crosses each edge where t reaches beyond
  // it); the grid when the centroid is outside the fluid mesh, and after the walk when t reaches beyond a
  // boundary edge of a visited triangle (t may re-enter a non-convex mesh).
  // hint: where the walk starts, updated to a triangle near t.
  template <class Visit>
  void for_each_piece(const Point t[3], int& hint, Visit&& visit);

 private:
  bool mark(int k) {
    if (stamp_of_[k] == stamp_) return false;
    stamp_of_[k] = stamp_;
    return true;
  }
  const FluidGrid& grid_;
  const Mesh& fluid_;
  std::vector<unsigned> stamp_of_;
  unsigned stamp_ = 0;
  std::vector<int> queue_;
};

template <class Visit>
void FluidSearch::for_each_piece(const Point t[3], int& hint, Visit&& visit) {
  if (++stamp_ == 0) {  // wrapped: clear the marks
    std::fill(stamp_of_.begin(), stamp_of_.end(), 0u);
    stamp_ = 1;
  }
  const Point centroid{(t[0].x + t[1].x + t[2].x) / 3, (t[0].y + t[1].y + t[2].y) / 3};
  const int start = locate(centroid, hint);
  Point k_corners[3];
  unsigned beyond;
  if (start >= 0) {
    fluid_.corners(start, k_corners);
    Piece first = clip(t, k_corners, beyond);
    if (first.n > 0) {
      hint = start;
      queue_.clear();
      queue_.push_back(start);
      mark(start);
      bool at_boundary = false;
      for (std::size_t q = 0; q < queue_.size(); ++q) {
        const int k = queue_[q];
        Piece piece = first;
        if (q > 0) {
          fluid_.corners(k, k_corners);
          piece = clip(t, k_corners, beyond);
          if (piece.n == 0) continue;
        }
        visit(k, piece);
        // Across edge i (opposite vertex i: clip's edge i + 1) only where t reaches beyond its line.
        for (int i = 0; i < 3; ++i) {
          if (!(beyond & (1u << ((i + 1) % 3)))) continue;
          const int nb = fluid_.neighbours[k][i];
          if (nb < 0) at_boundary = true;
          else if (mark(nb)) queue_.push_back(nb);
        }
      }
      // The walk reached every piece unless t leaves the fluid mesh across a boundary edge of a visited
      // triangle: on a non-convex mesh (a notch, a hole) t may come back in elsewhere, and the part of t
      // inside is then disconnected. The grid finds the other parts (the marks skip what the walk tested).
      if (!at_boundary) return;
    }
  }
  // The centroid is outside the fluid mesh (or its triangle misses a sliver t), or t may leave and re-enter
  // the mesh: test the grid's candidates.
  Point lo{std::min({t[0].x, t[1].x, t[2].x}), std::min({t[0].y, t[1].y, t[2].y})};
  Point hi{std::max({t[0].x, t[1].x, t[2].x}), std::max({t[0].y, t[1].y, t[2].y})};
  grid_.for_each_in_box(lo, hi, [&](int k) {
    if (!mark(k)) return;
    fluid_.corners(k, k_corners);
    Piece piece = clip(t, k_corners);
    if (piece.n > 0) {
      hint = k;
      visit(k, piece);
    }
  });
}

}  // namespace dlmfsi
