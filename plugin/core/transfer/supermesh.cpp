#include "transfer/supermesh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>

#include "geometry/clip.hpp"
#include "errors.hpp"
#include "mesh/fluid_search.hpp"
#include "geometry/predicates.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

// The fan apex of a convex polygon that maximises the smallest fan triangle (twice its area).
int best_apex(const Piece& piece) {
  int best = 0;
  double best_min = -1e300;
  for (int s = 0; s < piece.n; ++s) {
    double smallest = 1e300;
    for (int i = 1; i + 1 < piece.n; ++i)
      smallest = std::min(smallest, area2(piece.v[s], piece.v[(s + i) % piece.n], piece.v[(s + i + 1) % piece.n]));
    if (smallest > best_min) {
      best_min = smallest;
      best = s;
    }
  }
  return best;
}

// Is the segment [p, q] on the line of the segment [u, w], within 1e-10 of |w - u|?
bool on_segment_line(Point p, Point q, Point u, Point w) {
  const Point d = w - u;
  const double tol = 1e-10 * (d.x * d.x + d.y * d.y);
  return std::fabs(cross(d, p - u)) <= tol && std::fabs(cross(d, q - u)) <= tol;
}

// The local boundary edge of triangle k of m that holds [p, q], or -1.
int boundary_edge_holding(const Mesh& m, int k, Point p, Point q) {
  for (int e = 0; e < 3; ++e)
    if (m.neighbours[k][e] < 0 && on_segment_line(p, q, m.vertex(k, (e + 1) % 3), m.vertex(k, (e + 2) % 3))) return e;
  return -1;
}


// Merges the raw piece corners into vertices: points closer than tol (Chebyshev distance, taken
// transitively) become one vertex. Bit-identical copies always merge; the tolerance also merges a crossing
// point with the mesh vertex it nearly hits (an edge of one mesh passing through a vertex of the other in
// real arithmetic but not in floating point), which would otherwise leave slivers of area 1e-18 and, once
// a flat one is dropped, a hole. tol = 1e-12 of the overlap's bounding box diameter, and at most 1e-3 of
// the shortest edge of a and b, so that no two vertices of one mesh merge. A cluster's vertex is a vertex
// of a if it has one, else of b, else its first point in lexicographic order.
void merge_points(const Mesh& a, const Mesh& b, const std::vector<Point>& raw, std::vector<Point>& vertices,
                  std::vector<int>& id) {
  const size_t n = raw.size();
  id.assign(n, -1);
  vertices.clear();
  if (n == 0) return;
  Point lo = raw[0], hi = raw[0];
  for (Point p : raw) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  double hmin = 1e300;
  for (const Mesh* m : {&a, &b})
    for (int k = 0; k < m->size(); ++k)
      for (int i = 0; i < 3; ++i) {
        const Point d = m->vertex(k, (i + 1) % 3) - m->vertex(k, i);
        hmin = std::min(hmin, std::max(std::fabs(d.x), std::fabs(d.y)));
      }
  const double tol = std::min(1e-12 * std::hypot(hi.x - lo.x, hi.y - lo.y), 1e-3 * hmin);

  // Sort lexicographically; equal points are neighbours, near points are found by a sweep in x.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return raw[i].x < raw[j].x || (raw[i].x == raw[j].x && (raw[i].y < raw[j].y || (raw[i].y == raw[j].y && i < j)));
  });
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto unite = [&](int i, int j) {
    i = find(i);
    j = find(j);
    if (i != j) parent[std::max(i, j)] = std::min(i, j);
  };
  // Distinct values only in the sweep (copies are united directly), so a line of points with one x costs
  // one comparison per pair of distinct points that are near in x: O(n) for meshes that are not degenerate.
  std::vector<int> distinct;
  for (size_t r = 0; r < n; ++r) {
    if (r > 0 && raw[order[r]] == raw[order[r - 1]]) {
      unite(order[r], order[r - 1]);
      continue;
    }
    distinct.push_back(order[r]);
  }
  if (tol > 0) {
    // Sorted by x then y: for each point, the later points with x within tol; among those with the same
    // x, stop at the first beyond y + tol.
    for (size_t r = 0; r < distinct.size(); ++r) {
      const Point p = raw[distinct[r]];
      for (size_t s = r + 1; s < distinct.size(); ++s) {
        const Point q = raw[distinct[s]];
        if (q.x - p.x > tol) break;
        if (q.x == p.x && q.y - p.y > tol) {
          // skip the rest of this x-column
          while (s + 1 < distinct.size() && raw[distinct[s + 1]].x == p.x) ++s;
          continue;
        }
        if (std::fabs(q.y - p.y) <= tol) unite(distinct[r], distinct[s]);
      }
    }
  }

  // Which raw points are vertices of a (rank 0) or b (rank 1)? Everything else: rank 2.
  auto key_less = [](Point p, Point q) { return p.x < q.x || (p.x == q.x && p.y < q.y); };
  std::vector<Point> va(a.vertices), vb(b.vertices);
  std::sort(va.begin(), va.end(), key_less);
  std::sort(vb.begin(), vb.end(), key_less);
  auto rank = [&](Point p) {
    auto in = [&](const std::vector<Point>& v) {
      auto it = std::lower_bound(v.begin(), v.end(), p, key_less);
      return it != v.end() && *it == p;
    };
    return in(va) ? 0 : (in(vb) ? 1 : 2);
  };
  // The representative of each cluster, then the vertex numbers in lexicographic order of first appearance.
  std::vector<int> best(n, -1), best_rank(n, 3);
  for (int i : order) {
    const int c = find(i);
    const int r = rank(raw[i]);
    if (r < best_rank[c]) {
      best_rank[c] = r;
      best[c] = i;
    }
  }
  std::vector<int> number(n, -1);
  for (int i : order) {
    const int c = find(i);
    if (number[c] < 0) {
      number[c] = static_cast<int>(vertices.size());
      vertices.push_back(raw[best[c]]);
    }
    id[i] = number[c];
  }
}
}  // namespace

Supermesh build_supermesh(const Mesh& a, const Mesh& b) {
  for (const Mesh* m : {&a, &b})
    if (static_cast<int>(m->neighbours.size()) != m->size()) throw Error("supermesh: mesh adjacency not built");
  Supermesh out;
  if (a.size() == 0 || b.size() == 0) return out;

  // Fan triangles with their corners as raw points (merged below).
  std::vector<Point> raw;
  std::vector<std::array<int, 3>> raw_triangles;
  std::vector<int> raw_a, raw_b;
  FluidGrid grid(b);
  check_mesh_planar(a, FluidGrid(a), "supermesh: the first mesh");
  check_mesh_planar(b, grid, "supermesh: the second mesh");
  FluidSearch search(grid);
  int hint = 0;
  for (int ka = 0; ka < a.size(); ++ka) {
    Point t[3];
    a.corners(ka, t);
    search.for_each_piece(t, hint, [&](int kb, const Piece& piece) {
      ++out.pieces;
      const int first = static_cast<int>(raw.size());
      const int s = best_apex(piece);
      for (int i = 0; i < piece.n; ++i) raw.push_back(piece.v[(s + i) % piece.n]);
      for (int i = 1; i + 1 < piece.n; ++i) {
        raw_triangles.push_back({first, first + i, first + i + 1});
        raw_a.push_back(ka);
        raw_b.push_back(kb);
      }
    });
  }

  std::vector<int> id;
  merge_points(a, b, raw, out.vertices, id);

  for (size_t t = 0; t < raw_triangles.size(); ++t) {
    const auto& rt = raw_triangles[t];
    const std::array<int, 3> v{id[rt[0]], id[rt[1]], id[rt[2]]};
    const Point p = out.vertices[v[0]], q = out.vertices[v[1]], r = out.vertices[v[2]];
    const double a2 = area2(p, q, r);
    const bool collapsed = v[0] == v[1] || v[1] == v[2] || v[2] == v[0];
    if (collapsed || !(a2 > 0) || orient2d(p, q, r) <= 0) {
      ++(collapsed ? out.collapsed : out.dropped);
      out.dropped_area += 0.5 * std::fabs(area2(raw[rt[0]], raw[rt[1]], raw[rt[2]]));
      continue;
    }
    out.triangles.push_back(v);
    out.parent_a.push_back(raw_a[t]);
    out.parent_b.push_back(raw_b[t]);
    out.area += 0.5 * a2;
  }

  // Edges used once are boundary edges; find the parent boundary edge they lie on.
  std::vector<std::tuple<int, int, int>> edges;  // (min vertex, max vertex, 3 * triangle + local edge)
  edges.reserve(3 * out.triangles.size());
  for (int k = 0; k < out.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const int p = out.triangles[k][(i + 1) % 3], q = out.triangles[k][(i + 2) % 3];
      edges.emplace_back(std::min(p, q), std::max(p, q), 3 * k + i);
    }
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size();) {
    size_t f = e + 1;
    while (f < edges.size() && std::get<0>(edges[f]) == std::get<0>(edges[e]) &&
           std::get<1>(edges[f]) == std::get<1>(edges[e]))
      ++f;
    if (f - e > 2)
      throw Error("supermesh: an edge is shared by " + std::to_string(f - e) +
                  " triangles (are both meshes conforming, without overlapping triangles?)");
    if (f - e == 1) {
      const int k = std::get<2>(edges[e]) / 3, i = std::get<2>(edges[e]) % 3;
      const Point p = out.vertices[out.triangles[k][(i + 1) % 3]], q = out.vertices[out.triangles[k][(i + 2) % 3]];
      Supermesh::BoundaryEdge be{k, i, -1, -1};
      if ((be.parent_edge = boundary_edge_holding(a, out.parent_a[k], p, q)) >= 0)
        be.side = 0;
      else if ((be.parent_edge = boundary_edge_holding(b, out.parent_b[k], p, q)) >= 0)
        be.side = 1;
      out.boundary.push_back(be);
    }
    e = f;
  }
  std::sort(out.boundary.begin(), out.boundary.end(), [](const auto& x, const auto& y) {
    return x.triangle < y.triangle || (x.triangle == y.triangle && x.edge < y.edge);
  });
  return out;
}

}  // namespace dlmfsi
