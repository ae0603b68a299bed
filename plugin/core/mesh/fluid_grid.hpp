// A uniform bucket grid over the elements of a fluid simplex mesh, for either dimension.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <mutex>
#include <vector>

namespace dlmfsi {

// The grid over the elements' bounding boxes, about one element per cell: the fallback for point location
// and for elements whose search cannot start from an interior point. Built on first use (a solid inside the
// fluid never asks it), once, also when several threads ask at the same time. Elements describes the mesh
// (Triangles in fluid_search.hpp, Tetrahedra in fluid_search3d.hpp): its Mesh and Point types, kDim,
// kCorners, coordinate(p, a) and cells_per_axis.
template <class Elements>
class FluidGridOf {
 public:
  static constexpr int D = Elements::kDim;
  using MeshT = typename Elements::Mesh;
  using PointT = typename Elements::Point;

  explicit FluidGridOf(const MeshT& fluid) : fluid_(fluid) {}
  const MeshT& fluid() const { return fluid_; }

  // Calls f(k) for every fluid element whose bounding box meets the box [lo, hi] (with repetitions).
  template <class F>
  void for_each_in_box(PointT lo, PointT hi, F&& f) const {
    const PointT box[2] = {lo, hi};
    for_each_near(box, 2, f);
  }
  // The same for the bounding box of the n points p.
  template <class F>
  void for_each_near(const PointT* p, int n, F&& f) const {
    std::call_once(built_, [this] { build(); });
    int i0[D], i1[D];
    if (!cells_of(p, n, i0, i1)) return;
    for_each_cell(i0, i1, [&](std::size_t c) {
      for (int s = start_[c]; s < start_[c + 1]; ++s) f(items_[s]);
    });
  }

 private:
  // The range of cells [i0, i1] (per axis) that the bounding box of the n points p meets; false when it
  // misses the grid.
  bool cells_of(const PointT* p, int n, int* i0, int* i1) const;
  // The cells and their elements, built by the first for_each_near (the members it sets are mutable).
  void build() const;
  // Calls f(c) for the cells of the range [i0, i1], the first axis running fastest.
  template <class F>
  void for_each_cell(const int* i0, const int* i1, F&& f) const {
    int i[D];
    std::copy(i0, i0 + D, i);
    for (;;) {
      std::size_t c = 0;
      for (int a = D - 1; a >= 0; --a) c = c * n_[a] + i[a];
      f(c);
      int a = 0;
      while (a < D && i[a] == i1[a]) {
        i[a] = i0[a];
        ++a;
      }
      if (a == D) return;
      ++i[a];
    }
  }

  const MeshT& fluid_;
  mutable std::once_flag built_;
  mutable double lo_[D] = {}, hi_[D] = {}, inv_[D] = {};
  mutable int n_[D] = {};
  mutable std::vector<int> start_, items_;
};

template <class Elements>
void FluidGridOf<Elements>::build() const {
  const MeshT& fluid = fluid_;
  const int nt = fluid.size();
  std::fill(n_, n_ + D, 1);
  if (nt == 0) {
    start_.assign(2, 0);
    return;
  }
  std::fill(lo_, lo_ + D, HUGE_VAL);
  std::fill(hi_, hi_ + D, -HUGE_VAL);
  for (int k = 0; k < nt; ++k)
    for (int v = 0; v < Elements::kCorners; ++v)
      for (int a = 0; a < D; ++a) {
        const double x = Elements::coordinate(fluid.vertex(k, v), a);
        lo_[a] = std::min(lo_[a], x);
        hi_[a] = std::max(hi_[a], x);
      }
  double w[D];
  for (int a = 0; a < D; ++a) w[a] = std::max(hi_[a] - lo_[a], 1e-300);
  Elements::cells_per_axis(nt, w, n_);
  std::size_t cells = 1;
  for (int a = 0; a < D; ++a) {
    inv_[a] = n_[a] / w[a];
    cells *= static_cast<std::size_t>(n_[a]);
  }
  std::vector<int> count(cells + 1, 0);
  // Each element's range of cells (i0 then i1, D each), found once for the two passes.
  std::vector<int> range(static_cast<std::size_t>(nt) * 2 * D);
  for (int k = 0; k < nt; ++k) {
    PointT c[Elements::kCorners];
    fluid.corners(k, c);
    int* r = &range[static_cast<std::size_t>(k) * 2 * D];
    cells_of(c, Elements::kCorners, r, r + D);
  }
  auto boxes = [&](auto&& f) {
    for (int k = 0; k < nt; ++k) {
      const int* r = &range[static_cast<std::size_t>(k) * 2 * D];
      for_each_cell(r, r + D, [&](std::size_t cell) { f(cell, k); });
    }
  };
  boxes([&](std::size_t c, int) { ++count[c + 1]; });
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.resize(count.back());
  boxes([&](std::size_t c, int k) { items_[count[c]++] = k; });
}

template <class Elements>
bool FluidGridOf<Elements>::cells_of(const PointT* p, int n, int* i0, int* i1) const {
  if (fluid_.size() == 0) return false;
  double l[D], h[D];
  for (int a = 0; a < D; ++a) {
    l[a] = h[a] = Elements::coordinate(p[0], a);
    for (int j = 1; j < n; ++j) {
      l[a] = std::min(l[a], Elements::coordinate(p[j], a));
      h[a] = std::max(h[a], Elements::coordinate(p[j], a));
    }
    if (h[a] < lo_[a] || l[a] > hi_[a]) return false;
  }
  // Clamped before the conversion to int: a far (finite) point gives values beyond the int range, whose
  // conversion is undefined behaviour (UBSan: float-cast-overflow).
  auto cell = [this](double v, int a) {
    return static_cast<int>(std::max(0.0, std::min(static_cast<double>(n_[a] - 1), std::floor((v - lo_[a]) * inv_[a]))));
  };
  for (int a = 0; a < D; ++a) {
    i0[a] = cell(l[a], a);
    i1[a] = cell(h[a], a);
  }
  return true;
}

}  // namespace dlmfsi
