// Laying a simplex mesh (Mesh or Mesh3) out in another element order, for either dimension.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace dlmfsi {

// The element numbers sorted by their keys, ties by element number: keyed[k] = {key, k} in order of k (both
// callers build it so), and a least-significant-digit radix sort (three stable passes of 11 bits, the three
// digits' counts taken in one reading) keeps the order of equal keys, so the result is that of sorting the
// pairs (key, k), in O(n). The last pass writes the element numbers alone.
inline std::vector<int> order_by_key(std::vector<std::pair<uint32_t, int>> keyed) {
  constexpr int kBits = 11, kBuckets = 1 << kBits, kPasses = 3;
  std::vector<std::size_t> start(kPasses * kBuckets, 0);
  for (const auto& e : keyed)
    for (int p = 0; p < kPasses; ++p) ++start[p * kBuckets + ((e.first >> (p * kBits)) & (kBuckets - 1))];
  for (int p = 0; p < kPasses; ++p) {
    std::size_t at = 0;
    for (int b = 0; b < kBuckets; ++b) at += std::exchange(start[p * kBuckets + b], at);
  }
  std::vector<std::pair<uint32_t, int>> other(keyed.size());
  std::vector<int> order(keyed.size());
  for (int p = 0; p < kPasses; ++p) {
    std::size_t* s = &start[p * kBuckets];
    const int shift = p * kBits;
    if (p + 1 == kPasses) {
      for (const auto& e : keyed) order[s[(e.first >> shift) & (kBuckets - 1)]++] = e.second;
      break;
    }
    for (const auto& e : keyed) other[s[(e.first >> shift) & (kBuckets - 1)]++] = e;
    keyed.swap(other);
  }
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
