#include "mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "errors.hpp"
#include "predicates.hpp"

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

}  // namespace dlmfsi
