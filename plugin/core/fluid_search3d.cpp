#include "fluid_search3d.hpp"

#include <algorithm>
#include <cmath>

#include "predicates3d.hpp"

namespace dlmfsi {

FluidGrid3::FluidGrid3(const Mesh3& fluid) : fluid_(fluid) {
  const int nt = fluid.size();
  if (nt == 0) {
    start_.assign(2, 0);
    return;
  }
  for (int a = 0; a < 3; ++a) {
    lo_[a] = HUGE_VAL;
    hi_[a] = -HUGE_VAL;
  }
  for (const auto& t : fluid.tetrahedra)
    for (int v : t) {
      const Point3 p = fluid.vertices[v];
      const double c[3] = {p.x, p.y, p.z};
      for (int a = 0; a < 3; ++a) {
        lo_[a] = std::min(lo_[a], c[a]);
        hi_[a] = std::max(hi_[a], c[a]);
      }
    }
  double w[3], volume = 1;
  for (int a = 0; a < 3; ++a) {
    w[a] = std::max(hi_[a] - lo_[a], 1e-300);
    volume *= w[a];
  }
  // About one tetrahedron per cell, cells roughly cubic (clamped as doubles: converting a double beyond
  // the int range is undefined behaviour).
  const double side = std::cbrt(volume / nt);
  for (int a = 0; a < 3; ++a) {
    n_[a] = static_cast<int>(std::max(1.0, std::min(1024.0, w[a] / side)));
    inv_[a] = n_[a] / w[a];
  }
  std::vector<int> count(static_cast<size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
  auto boxes = [&](auto&& f) {
    for (int k = 0; k < nt; ++k) {
      Point3 c[4];
      fluid.corners(k, c);
      Point3 lo = c[0], hi = c[0];
      for (int i = 1; i < 4; ++i) {
        lo = {std::min(lo.x, c[i].x), std::min(lo.y, c[i].y), std::min(lo.z, c[i].z)};
        hi = {std::max(hi.x, c[i].x), std::max(hi.y, c[i].y), std::max(hi.z, c[i].z)};
      }
      int i0[3], i1[3];
      cells_of(lo, hi, i0, i1);
      for (int z = i0[2]; z <= i1[2]; ++z)
        for (int y = i0[1]; y <= i1[1]; ++y)
          for (int x = i0[0]; x <= i1[0]; ++x) f((static_cast<size_t>(z) * n_[1] + y) * n_[0] + x, k);
    }
  };
  boxes([&](size_t c, int) { ++count[c + 1]; });
  for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.resize(count.back());
  boxes([&](size_t c, int k) { items_[count[c]++] = k; });
}

bool FluidGrid3::cells_of(Point3 lo, Point3 hi, int* i0, int* i1) const {
  const double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
  if (fluid_.size() == 0) return false;
  for (int a = 0; a < 3; ++a)
    if (h[a] < lo_[a] || l[a] > hi_[a]) return false;
  // Clamped before the conversion to int (a far, finite point gives values beyond the int range).
  auto cell = [this](double v, int a) {
    return static_cast<int>(std::max(0.0, std::min(static_cast<double>(n_[a] - 1), std::floor((v - lo_[a]) * inv_[a]))));
  };
  for (int a = 0; a < 3; ++a) {
    i0[a] = cell(l[a], a);
    i1[a] = cell(h[a], a);
  }
  return true;
}

FluidSearch3::FluidSearch3(const FluidGrid3& grid)
    : grid_(grid), fluid_(grid.fluid()), stamp_of_(grid.fluid().size(), 0u) {}

namespace {

// The side of p with respect to face i of tetrahedron k: +1 on the tetrahedron's side.
inline int side(const Mesh3& m, int k, int i, Point3 p) {
  Point3 c[4];
  m.corners(k, c);
  c[i] = p;
  return orient3d(c[0], c[1], c[2], c[3]);
}

}  // namespace

int FluidSearch3::locate(Point3 p, int hint) const {
  const Mesh3& m = fluid_;
  if (hint >= 0 && hint < m.size()) {
    // Visibility walk: step across a face that has p strictly on its far side; the face tried first
    // rotates so that the walk cannot cycle for long (bounded anyway).
    int k = hint;
    const int max_steps = 64 + 8 * static_cast<int>(std::cbrt(static_cast<double>(m.size())));
    for (int step = 0; step < max_steps; ++step) {
      int next = -2;
      for (int r = 0; r < 4; ++r) {
        const int i = (r + step) % 4;
        if (side(m, k, i, p) < 0) {
          next = m.neighbours[k][i];
          break;
        }
      }
      if (next == -2) return k;  // p is in the closed tetrahedron k
      if (next < 0) break;       // p is beyond the boundary in this direction: ask the grid
      k = next;
    }
  }
  int found = -1;
  grid_.for_each_in_box(p, p, [&](int k) {
    if (found >= 0) return;
    if (side(m, k, 0, p) >= 0 && side(m, k, 1, p) >= 0 && side(m, k, 2, p) >= 0 && side(m, k, 3, p) >= 0) found = k;
  });
  return found;
}

}  // namespace dlmfsi
