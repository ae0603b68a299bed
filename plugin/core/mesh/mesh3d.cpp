#include "mesh/mesh3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <tuple>

#include "errors.hpp"
#include "mesh/mesh_order.hpp"
#include "geometry/predicates3d.hpp"

namespace dlmfsi {

void Mesh3::check() const {
  for (size_t v = 0; v < vertices.size(); ++v)
    if (!std::isfinite(vertices[v].x) || !std::isfinite(vertices[v].y) || !std::isfinite(vertices[v].z))
      throw Error("mesh vertex " + std::to_string(v) + " is not finite");
  const int nt = size();
  const int nv = static_cast<int>(vertices.size());
  for (int k = 0; k < nt; ++k) {
    for (int i = 0; i < 4; ++i)
      if (tetrahedra[k][i] < 0 || tetrahedra[k][i] >= nv)
        throw Error("tetrahedron " + std::to_string(k) + " has a bad vertex index");
    if (orient3d(vertex(k, 0), vertex(k, 1), vertex(k, 2), vertex(k, 3)) <= 0)
      throw Error("mesh tetrahedron " + std::to_string(k) + " is flat or negatively oriented");
  }
}

void Mesh3::build_adjacency() {
  check();
  const int nt = size();
  // Sort the faces by their sorted vertex triple; equal neighbours in the sorted list are the two sides.
  struct Face {
    std::array<int, 3> v;
    int at;  // 4 * tetrahedron + local face
    bool operator<(const Face& o) const { return v < o.v; }
  };
  std::vector<Face> faces;
  faces.reserve(4 * static_cast<size_t>(nt));
  for (int k = 0; k < nt; ++k)
    for (int i = 0; i < 4; ++i) {
      std::array<int, 3> f{tetrahedra[k][(i + 1) % 4], tetrahedra[k][(i + 2) % 4], tetrahedra[k][(i + 3) % 4]};
      std::sort(f.begin(), f.end());
      faces.push_back({f, 4 * k + i});
    }
  std::sort(faces.begin(), faces.end());
  neighbours.assign(nt, {-1, -1, -1, -1});
  for (size_t e = 0; e < faces.size();) {
    size_t f = e + 1;
    while (f < faces.size() && faces[f].v == faces[e].v) ++f;
    if (f - e > 2) throw Error("mesh face shared by more than two tetrahedra");
    if (f - e == 2) {
      const int s = faces[e].at, t = faces[e + 1].at;
      neighbours[s / 4][s % 4] = t / 4;
      neighbours[t / 4][t % 4] = s / 4;
    }
    e = f;
  }
}

std::vector<int> morton_order(const Mesh3& mesh) {
  Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Point3& p : mesh.vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  auto scale = [](double l, double h) { return h > l ? 1023 / (h - l) : 0.0; };
  const double sx = scale(lo.x, hi.x), sy = scale(lo.y, hi.y), sz = scale(lo.z, hi.z);
  auto spread = [](uint32_t v) {  // bit i to bit 3i (10 bits)
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    return (v | (v << 2)) & 0x09249249u;
  };
  auto cell = [](double v, double l, double s) {
    return static_cast<uint32_t>(std::min(1023.0, std::max(0.0, (v - l) * s)));
  };
  std::vector<std::pair<uint32_t, int>> keyed(mesh.size());
  for (int k = 0; k < mesh.size(); ++k) {
    Point3 c[4];
    mesh.corners(k, c);
    const Point3 m = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    keyed[k] = {spread(cell(m.x, lo.x, sx)) | (spread(cell(m.y, lo.y, sy)) << 1) | (spread(cell(m.z, lo.z, sz)) << 2), k};
  }
  return order_by_key(std::move(keyed));
}

Mesh3 renumbered(const Mesh3& mesh, const std::vector<int>& order) {
  return renumbered_elements(mesh, order, &Mesh3::tetrahedra);
}

void check_tetrahedron_size(double det, const std::string& who, const char* side) {
  if (supported_tetrahedron_size(det)) return;
  char s[160];
  std::snprintf(s, sizeof s,
                " is too small or too large (volume %.3g in doubles): %s tetrahedra from about 1e-100 to 1e100 in"
                " size are supported",
                det / 6, side);
  throw Error(who + s);
}

}  // namespace dlmfsi
