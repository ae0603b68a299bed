#include "mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>

#include "errors.hpp"
#include "mesh/mesh_order.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

void Mesh::check() const {
  for (size_t v = 0; v < vertices.size(); ++v)
    if (!std::isfinite(vertices[v].x) || !std::isfinite(vertices[v].y))
      throw Error("mesh vertex " + std::to_string(v) + " is not finite");
  const int nt = size();
  const int nv = static_cast<int>(vertices.size());
  for (int k = 0; k < nt; ++k) {
    for (int i = 0; i < 3; ++i)
      if (triangles[k][i] < 0 || triangles[k][i] >= nv) throw Error("triangle " + std::to_string(k) + " has a bad vertex index");
    if (orient2d(vertex(k, 0), vertex(k, 1), vertex(k, 2)) <= 0)
      throw Error("mesh triangle " + std::to_string(k) + " is degenerate or clockwise");
  }
}

void Mesh::build_adjacency() {
  check();
  const int nt = size();
  // Sort the edges by their vertex pair; equal neighbours in the sorted list are the two sides of one edge.
  std::vector<std::tuple<int, int, int>> edges;  // (min vertex, max vertex, 3 * triangle + local edge)
  edges.reserve(3 * static_cast<size_t>(nt));
  for (int k = 0; k < nt; ++k)
    for (int i = 0; i < 3; ++i) {
      int a = triangles[k][(i + 1) % 3], b = triangles[k][(i + 2) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), 3 * k + i);
    }
  std::sort(edges.begin(), edges.end());
  neighbours.assign(nt, {-1, -1, -1});
  for (size_t e = 0; e < edges.size();) {
    size_t f = e + 1;
    while (f < edges.size() && std::get<0>(edges[f]) == std::get<0>(edges[e]) && std::get<1>(edges[f]) == std::get<1>(edges[e])) ++f;
    if (f - e > 2) throw Error("mesh edge shared by more than two triangles");
    if (f - e == 2) {
      int s = std::get<2>(edges[e]), t = std::get<2>(edges[e + 1]);
      neighbours[s / 3][s % 3] = t / 3;
      neighbours[t / 3][t % 3] = s / 3;
    }
    e = f;
  }
}

std::vector<int> morton_order(const Mesh& mesh) {
  Point lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Point& p : mesh.vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const double sx = hi.x > lo.x ? 65535 / (hi.x - lo.x) : 0, sy = hi.y > lo.y ? 65535 / (hi.y - lo.y) : 0;
  auto spread = [](uint32_t v) {  // bit i to bit 2i
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    return (v | (v << 1)) & 0x55555555u;
  };
  std::vector<std::pair<uint32_t, int>> keyed(mesh.size());
  for (int k = 0; k < mesh.size(); ++k) {
    Point c[3];
    mesh.corners(k, c);
    const double x = (c[0].x + c[1].x + c[2].x) / 3, y = (c[0].y + c[1].y + c[2].y) / 3;
    const auto ix = static_cast<uint32_t>(std::min(65535.0, std::max(0.0, (x - lo.x) * sx)));
    const auto iy = static_cast<uint32_t>(std::min(65535.0, std::max(0.0, (y - lo.y) * sy)));
    keyed[k] = {spread(ix) | (spread(iy) << 1), k};
  }
  return order_by_key(std::move(keyed));
}

Mesh renumbered(const Mesh& mesh, const std::vector<int>& order) {
  return renumbered_elements(mesh, order, &Mesh::triangles);
}

}  // namespace dlmfsi
