#include "fluid_search.hpp"

#include <algorithm>
#include <cmath>

#include "predicates.hpp"

namespace dlmfsi {

FluidGrid::FluidGrid(const Mesh& fluid) : fluid_(fluid) {
  const int nt = fluid.size();
  if (nt == 0) {
    start_.assign(2, 0);
    return;
  }
  lo_ = hi_ = fluid.vertices[fluid.triangles[0][0]];
  for (const auto& t : fluid.triangles)
    for (int v : t) {
      const Point p = fluid.vertices[v];
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y)};
    }
  const double w = std::max(hi_.x - lo_.x, 1e-300), h = std::max(hi_.y - lo_.y, 1e-300);
  // About one triangle per cell, cells roughly square.
  // (clamped as doubles: converting a double beyond the int range is undefined behaviour)
  nx_ = static_cast<int>(std::max(1.0, std::min(4096.0, std::sqrt(nt * w / h))));
  ny_ = static_cast<int>(std::max(1.0, std::min(4096.0, std::sqrt(nt * h / w))));
  inv_dx_ = nx_ / w;
  inv_dy_ = ny_ / h;
  std::vector<int> count(static_cast<size_t>(nx_) * ny_ + 1, 0);
  auto boxes = [&](auto&& f) {
    for (int k = 0; k < nt; ++k) {
      Point c[3];
      fluid.corners(k, c);
      int i0, j0, i1, j1;
      cells_of({std::min({c[0].x, c[1].x, c[2].x}), std::min({c[0].y, c[1].y, c[2].y})},
               {std::max({c[0].x, c[1].x, c[2].x}), std::max({c[0].y, c[1].y, c[2].y})}, i0, j0, i1, j1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(j * nx_ + i, k);
    }
  };
  boxes([&](int c, int) { ++count[c + 1]; });
  for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.resize(count.back());
  boxes([&](int c, int k) { items_[count[c]++] = k; });
}

bool FluidGrid::cells_of(Point lo, Point hi, int& i0, int& j0, int& i1, int& j1) const {
  if (fluid_.size() == 0 || hi.x < lo_.x || hi.y < lo_.y || lo.x > hi_.x || lo.y > hi_.y) return false;
  // Clamped before the conversion to int: a far (finite) triangle gives values beyond the int range,
  // whose conversion is undefined behaviour (UBSan: float-cast-overflow).
  auto cell = [](double v, double origin, double inv, int n) {
    return static_cast<int>(std::max(0.0, std::min(static_cast<double>(n - 1), std::floor((v - origin) * inv))));
  };
  i0 = cell(lo.x, lo_.x, inv_dx_, nx_);
  i1 = cell(hi.x, lo_.x, inv_dx_, nx_);
  j0 = cell(lo.y, lo_.y, inv_dy_, ny_);
  j1 = cell(hi.y, lo_.y, inv_dy_, ny_);
  return true;
}

FluidSearch::FluidSearch(const FluidGrid& grid)
    : grid_(grid), fluid_(grid.fluid()), stamp_of_(grid.fluid().size(), 0u) {}

int FluidSearch::locate(Point p, int hint) const {
  const Mesh& m = fluid_;
  if (hint >= 0 && hint < m.size()) {
    // Visibility walk: step across an edge that has p strictly on its far side; the edge to try first
    // rotates so that the walk cannot cycle on non-Delaunay meshes for long (bounded anyway).
    int k = hint;
    const int max_steps = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(m.size())));
    for (int step = 0; step < max_steps; ++step) {
      int next = -2;
      for (int r = 0; r < 3; ++r) {
        const int i = (r + step) % 3;
        if (orient2d(m.vertex(k, (i + 1) % 3), m.vertex(k, (i + 2) % 3), p) < 0) {
          next = m.neighbours[k][i];
          break;
        }
      }
      if (next == -2) return k;  // p is in the closed triangle k
      if (next < 0) break;       // p is beyond the boundary in this direction: ask the grid
      k = next;
    }
  }
  int found = -1;
  grid_.for_each_in_box(p, p, [&](int k) {
    if (found >= 0) return;
    if (orient2d(m.vertex(k, 0), m.vertex(k, 1), p) >= 0 && orient2d(m.vertex(k, 1), m.vertex(k, 2), p) >= 0 &&
        orient2d(m.vertex(k, 2), m.vertex(k, 0), p) >= 0)
      found = k;
  });
  return found;
}

}  // namespace dlmfsi
