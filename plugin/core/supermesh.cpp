#include "supermesh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>

#include "clip.hpp"
#include "errors.hpp"
#include "fluid_search.hpp"
#include "predicates.hpp"

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

  // Merge equal points (by value: -0 and +0 are one point).
  std::vector<int> order(raw.size()), id(raw.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return raw[i].x < raw[j].x || (raw[i].x == raw[j].x && (raw[i].y < raw[j].y || (raw[i].y == raw[j].y && i < j)));
  });
  for (size_t r = 0; r < order.size(); ++r) {
    if (r == 0 || raw[order[r]] != raw[order[r - 1]]) out.vertices.push_back(raw[order[r]]);
    id[order[r]] = static_cast<int>(out.vertices.size()) - 1;
  }

  for (size_t t = 0; t < raw_triangles.size(); ++t) {
    const std::array<int, 3> v{id[raw_triangles[t][0]], id[raw_triangles[t][1]], id[raw_triangles[t][2]]};
    const Point p = out.vertices[v[0]], q = out.vertices[v[1]], r = out.vertices[v[2]];
    const double a2 = area2(p, q, r);
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0] || !(a2 > 0) || orient2d(p, q, r) <= 0) {
      ++out.dropped;
      out.dropped_area += 0.5 * std::fabs(a2);
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
