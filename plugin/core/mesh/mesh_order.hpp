// Laying a simplex mesh (Mesh or Mesh3) out in another element order, for either dimension.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace dlmfsi {

// The element numbers sorted by their keys (ties by element number).
inline std::vector<int> order_by_key(std::vector<std::pair<uint32_t, int>> keyed) {
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
  return order;
}

// The mesh with element i = mesh's element order[i] and the vertices numbered in the order the elements
// first use them (the same points and neighbours). elements: the mesh's element array (&Mesh::triangles,
// &Mesh3::tetrahedra).
template <class MeshT, class Elements>
MeshT renumbered_elements(const MeshT& mesh, const std::vector<int>& order, Elements MeshT::*elements) {
  const Elements& from = mesh.*elements;
  MeshT out;
  Elements& to = out.*elements;
  const int nt = mesh.size();
  const int corners = static_cast<int>(std::tuple_size<typename Elements::value_type>::value);
  std::vector<int> new_index(nt, -1), vertex_index(mesh.vertices.size(), -1);
  for (int i = 0; i < nt; ++i) new_index[order[i]] = i;
  to.resize(nt);
  out.vertices.reserve(mesh.vertices.size());
  for (int i = 0; i < nt; ++i)
    for (int c = 0; c < corners; ++c) {
      int& v = vertex_index[from[order[i]][c]];
      if (v < 0) {
        v = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[from[order[i]][c]]);
      }
      to[i][c] = v;
    }
  if (!mesh.neighbours.empty()) {
    out.neighbours.resize(nt);
    for (int i = 0; i < nt; ++i)
      for (int c = 0; c < corners; ++c) {
        const int n = mesh.neighbours[order[i]][c];
        out.neighbours[i][c] = n < 0 ? -1 : new_index[n];
      }
  }
  return out;
}

}  // namespace dlmfsi
