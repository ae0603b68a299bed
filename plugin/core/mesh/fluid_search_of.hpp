// Point location and piece enumeration over a fluid simplex mesh, for either dimension.
#pragma once
#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

#include "mesh/fluid_grid.hpp"

namespace dlmfsi {

// One per thread (it keeps visit marks). Elements describes the mesh (Triangles in fluid_search.hpp,
// Tetrahedra in fluid_search3d.hpp): besides what FluidGridOf uses, its Piece type, centroid(t),
// side(mesh, k, i, p) (the exact sign of p with respect to facet i of element k, opposite vertex i: +1 on
// the element's side), max_walk_steps(n), kClipHintFirst (does for_each_piece clip t against the hint
// before it locates t's centroid?), Faces (what clip prepares once from t), clip(t, faces, k, beyond)
// and reaches_beyond(piece, beyond, i) (t reaches beyond facet i of k there: its neighbour across may meet
// t; the walk visits every element whose piece has positive measure whenever it holds for each pair of pieces
// adjacent across a facet, with t crossing the facet's interior), and Rest with clip(t, faces, k, beyond,
// rest), rest_facet(rest), rest_piece(rest), rest_corners(rest): what clip tells of the part of t beyond one
// facet of k when t ∩ k is t's part on the inner side of that facet's line or plane (facet -1 otherwise).
// Elements::ElementPlanes, when Elements keeps something of each fluid element for clip (kept: then
// element_planes(mesh, k, out) forms it, and clip(t, faces, k_corners, planes, beyond) and side(mesh, k, i, p,
// planes) use it).
template <class Elements, class = void>
struct ElementPlanesOf {
  struct type {};
  static constexpr bool kept = false;
};
template <class Elements>
struct ElementPlanesOf<Elements, std::void_t<typename Elements::ElementPlanes>> {
  using type = typename Elements::ElementPlanes;
  static constexpr bool kept = true;
};

template <class Elements>
class FluidSearchOf {
 public:
  static constexpr int kCorners = Elements::kCorners;
  using MeshT = typename Elements::Mesh;
  using PointT = typename Elements::Point;
  using PieceT = typename Elements::Piece;

  explicit FluidSearchOf(const FluidGridOf<Elements>& grid)
      : grid_(grid), fluid_(grid.fluid()), max_walk_steps_(Elements::max_walk_steps(fluid_.size())),
        stamp_of_(grid.fluid().size(), 0u) {
    if constexpr (Planes::kept) {
      // formed on first use (a solid often meets a small part of the fluid); new[] leaves them unset
      planes_.reset(new typename Planes::type[static_cast<std::size_t>(fluid_.size())]);
      formed_.assign(static_cast<std::size_t>(fluid_.size()), 0);
    }
  }

  // A fluid element whose closed set contains p, by a visibility walk from hint (>= 0) with exact
  // predicates, falling back to the grid; -1 when p lies outside the fluid mesh.
  int locate(PointT p, int hint) const;

  // Calls visit(k, piece) once for every fluid element k whose interior meets the interior of the
  // positively oriented element t, with piece = t ∩ k. Advancing front: from the hint when it meets t
  // (kClipHintFirst) or else the element holding t's centroid, across fluid facets while pieces are
  // non-empty (the elements meeting a convex set are facet-connected through such elements, and a path
  // inside t crosses each facet where t reaches beyond its line or plane); the grid when the centroid is
  // outside the fluid mesh, and after the walk when t reaches beyond a boundary facet of a visited element
  // (t may re-enter a non-convex mesh). hint: where the walk starts, updated to an element that meets t.
  template <class Visit>
  void for_each_piece(const PointT t[kCorners], int& hint, Visit&& visit) {
    walk<false>(t, PointT(), hint, visit);
  }
  // The same with every piece in coordinates relative to origin: t and each fluid element met are translated
  // by -origin before they are clipped (Elements::translate), which decides every side as on the absolute
  // coordinates when the translation is exact, and constructs crossings to the local coordinates' ulp. Returns
  // false, having visited some pieces (to be discarded), when it is not exact for t or for an element met;
  // locating and walking use the absolute coordinates, so the elements visited are those of the overload above.
  template <class Visit>
  bool for_each_piece(const PointT t[kCorners], PointT origin, int& hint, Visit&& visit) {
    return walk<true>(t, origin, hint, visit);
  }

 private:
  // for_each_piece, with the pieces relative to origin when Local (then false when a translation is not exact).
  template <bool Local, class Visit>
  bool walk(const PointT t_absolute[kCorners], PointT origin, int& hint, Visit& visit);
  // Elements::side(fluid_, k, i, p), with what is kept of k when Elements keeps something.
  int side(int k, int i, PointT p) const {
    if constexpr (Planes::kept) return Elements::side(fluid_, k, i, p, planes(k));
    else return Elements::side(fluid_, k, i, p);
  }
  // What is kept of element k (when kept), formed on first use.
  const typename ElementPlanesOf<Elements>::type& planes(int k) const {
    const std::size_t at = static_cast<std::size_t>(k);
    if constexpr (Planes::kept) {
      if (!formed_[at]) {
        Elements::element_planes(fluid_, k, planes_[at]);
        formed_[at] = 1;
      }
    }
    return planes_[at];
  }
  // Does p lie in the closed element k?
  bool in_element(int k, PointT p) const {
    for (int i = 0; i < kCorners; ++i)
      if (side(k, i, p) < 0) return false;
    return true;
  }
  // Do the corners of t in mask (bit i: corner i) lie in the closed element k?
  bool holds_corners(int k, const PointT t[kCorners], unsigned mask) const {
    for (int c = 0; c < kCorners; ++c)
      if ((mask & (1u << c)) && !in_element(k, t[c])) return false;
    return true;
  }
  // t ∩ k, k's corners given (as clipped): with what is kept of k when Elements keeps something.
  PieceT clip(const PointT t[kCorners], const typename Elements::Faces& t_faces, int k,
              const PointT k_corners[kCorners], unsigned& beyond) const {
    if constexpr (Planes::kept) return Elements::clip(t, t_faces, k_corners, planes(k), beyond);
    else return Elements::clip(t, t_faces, k_corners, beyond);
  }
  // The same for the walk's first element, with what clip tells of t beyond a facet (an Elements that keeps
  // something of each element tells nothing there: rest stays as it is).
  PieceT clip_first(const PointT t[kCorners], const typename Elements::Faces& t_faces, int k,
                    const PointT k_corners[kCorners], unsigned& beyond, typename Elements::Rest& rest) const {
    if constexpr (Planes::kept) return clip(t, t_faces, k, k_corners, beyond);
    else return Elements::clip(t, t_faces, k_corners, beyond, rest);
  }
  bool mark(int k) {
    if (stamp_of_[k] == stamp_) return false;
    stamp_of_[k] = stamp_;
    return true;
  }
  const FluidGridOf<Elements>& grid_;
  const MeshT& fluid_;
  int max_walk_steps_;  // locate's bound, Elements::max_walk_steps of the fluid's size
  std::vector<unsigned> stamp_of_;
  unsigned stamp_ = 0;
  std::vector<int> queue_;
  using Planes = ElementPlanesOf<Elements>;
  // planes_[k]: what clip keeps of element k (when kept), set when formed_[k] (per thread: mutable in the
  // const searches)
  mutable std::unique_ptr<typename Planes::type[]> planes_;
  mutable std::vector<unsigned char> formed_;
};

template <class Elements>
int FluidSearchOf<Elements>::locate(PointT p, int hint) const {
  const MeshT& m = fluid_;
  if (hint >= 0 && hint < m.size()) {
    // Visibility walk: step across a facet that has p strictly on its far side; the facet tried first
    // rotates so that the walk cannot cycle on non-Delaunay meshes for long (bounded anyway).
    int k = hint;
    for (int step = 0; step < max_walk_steps_; ++step) {
      int next = -2;
      for (int r = 0; r < kCorners; ++r) {
        const int i = (r + step) % kCorners;
        if (side(k, i, p) < 0) {
          next = m.neighbours[k][i];
          break;
        }
      }
      if (next == -2) return k;  // p is in the closed element k
      if (next < 0) break;       // p is beyond the boundary in this direction: ask the grid
      k = next;
    }
  }
  int found = -1;
  grid_.for_each_in_box(p, p, [&](int k) {
    if (found < 0 && in_element(k, p)) found = k;
  });
  return found;
}

template <class Elements>
template <bool Local, class Visit>
bool FluidSearchOf<Elements>::walk(const PointT t_absolute[kCorners], PointT origin, int& hint, Visit& visit) {
  if (++stamp_ == 0) {  // wrapped: clear the marks
    std::fill(stamp_of_.begin(), stamp_of_.end(), 0u);
    stamp_ = 1;
  }
  // t: what is clipped (t translated when Local); t_absolute: what is located and walked.
  PointT t_local[kCorners];
  if constexpr (Local) {
    if (!Elements::translate(t_absolute, origin, t_local)) return false;
  }
  const PointT* t = Local ? t_local : t_absolute;
  typename Elements::Faces t_faces;  // what clip needs of t, formed once for all the elements it meets
  t_faces.set(t);
  PointT k_corners[kCorners];
  // the corners of fluid element k as clipped: translated when Local (false when not exactly)
  auto corners_of = [&](int k) {
    fluid_.corners(k, k_corners);
    if constexpr (Local) return Elements::translate(k_corners, origin, k_corners);
    return true;
  };
  unsigned beyond;
  // The front may start from any element that meets t: with kClipHintFirst the hint's first (the last
  // element's start, which meets t when the elements come in an order that keeps neighbours together),
  // else the one holding t's centroid.
  int start = -1;
  PieceT first;
  typename Elements::Rest rest;
  if (Elements::kClipHintFirst && hint >= 0 && hint < fluid_.size()) {
    if (!corners_of(hint)) return false;
    first = clip_first(t, t_faces, hint, k_corners, beyond, rest);
    if (first.n > 0) start = hint;
  }
  if (start < 0) {
    start = locate(Elements::centroid(t_absolute), hint);
    if (start >= 0 && !(Elements::kClipHintFirst && start == hint)) {  // the hint's piece is empty already
      if (!corners_of(start)) return false;
      first = clip_first(t, t_faces, start, k_corners, beyond, rest);
    }
  }
  if (start >= 0) {
    if (first.n > 0) {
      hint = start;
      // t ∩ start is t's part on the inner side of one facet's line: t lies in start and the neighbour
      // across that facet when t's corners beyond it lie in that closed neighbour (the rest's other corners
      // are on the facet, where it crosses t's edges properly), and then the two pieces are all (the mesh
      // conforms).
      const int facet = Elements::rest_facet(rest);
      const int across = facet >= 0 ? fluid_.neighbours[start][facet] : -1;
      if (across >= 0 && holds_corners(across, t_absolute, Elements::rest_corners(rest))) {
        // across's corners are start's but one, which lies beyond the facet: translated exactly too?
        if (Local && !corners_of(across)) return false;
        visit(start, first);
        visit(across, *Elements::rest_piece(rest));
        return true;
      }
      queue_.clear();
      queue_.push_back(start);
      mark(start);
      bool at_boundary = false;
      // visits k's piece, then queues the neighbours across the facets where t reaches beyond it
      auto spread = [&](int k, const PieceT& piece) {
        visit(k, piece);
        for (int i = 0; i < kCorners; ++i) {
          if (!Elements::reaches_beyond(piece, beyond, i)) continue;
          const int nb = fluid_.neighbours[k][i];
          if (nb < 0) at_boundary = true;
          else if (mark(nb)) queue_.push_back(nb);
        }
      };
      spread(start, first);
      for (std::size_t q = 1; q < queue_.size(); ++q) {
        const int k = queue_[q];
        if (!corners_of(k)) return false;
        const PieceT piece = clip(t, t_faces, k, k_corners, beyond);
        if (piece.n > 0) spread(k, piece);
      }
      // The walk reached every piece unless t leaves the fluid mesh across a boundary facet of a visited
      // element: on a non-convex mesh (a notch, a hole) t may come back in elsewhere, and the part of t
      // inside is then disconnected. The grid finds the other parts (the marks skip what the walk tested).
      if (!at_boundary) return true;
    }
  }
  // The centroid is outside the fluid mesh (or its element misses a sliver t), or t may leave and re-enter
  // the mesh: test the grid's candidates.
  bool exact = true;
  grid_.for_each_near(t_absolute, kCorners, [&](int k) {
    if (!exact || !mark(k)) return;
    if (!corners_of(k)) {
      exact = false;
      return;
    }
    const PieceT piece = clip(t, t_faces, k, k_corners, beyond);
    if (piece.n > 0) {
      hint = k;
      visit(k, piece);
    }
  });
  return exact;
}

}  // namespace dlmfsi
