// Test helpers for the 3D core: tetrahedra, their splits, and the checks of a piece's shape.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "geometry/clip3d.hpp"
#include "geometry/predicates3d.hpp"
#include "reference3d.hpp"

namespace dlmfsi::test3d {

using Tet = std::array<Point3, 4>;

inline double tet_volume(const Tet& t) { return volume6(t[0], t[1], t[2], t[3]) / 6; }

// Orders t positively; false when it is flat (exactly).
inline bool make_positive(Tet& t) {
  const int o = orient3d(t[0], t[1], t[2], t[3]);
  if (o == 0) return false;
  if (o < 0) std::swap(t[2], t[3]);
  return true;
}

inline bool finite(const Tet& t) {
  for (Point3 p : t)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

// The largest |coordinate| and the diameter of the bounding box of two tetrahedra: the round-off floor
// of a constructed vertex is about eps * M, that of a volume eps * M * D^2.
inline void scales(const Tet& a, const Tet& b, double& m, double& d) {
  Point3 lo = a[0], hi = a[0];
  m = 0;
  for (const Tet* t : {&a, &b})
    for (Point3 p : *t) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    }
  d = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

// Splits t into four tetrahedra about its centroid, t_k = t with vertex k replaced by the centroid
// (positively oriented, sharing faces pairwise); false when the rounded centroid is not strictly inside.
inline bool split4(const Tet& t, Tet out[4]) {
  const Point3 c = 0.25 * (t[0] + t[1] + t[2] + t[3]);
  for (int k = 0; k < 4; ++k) {
    out[k] = t;
    out[k][k] = c;
    if (orient3d(out[k][0], out[k][1], out[k][2], out[k][3]) <= 0) return false;
  }
  return true;
}

// The shape of a piece of a and b: empty or at least 4 finite vertices; faces ordered from the exact plane
// sets; Euler's V - E + F = 2; every vertex within tol of the closed a and b, and of its faces' planes.
// Returns an empty string when it holds, else what failed.
inline std::string piece_shape(const Piece3& p, const Tet& a, const Tet& b, double tol) {
  if (p.n == 0) return "";
  if (p.n < 4) return "fewer than 4 vertices";
  if (!p.exact) return "a face ordered by the floating-point guard";
  for (int k = 0; k < p.n; ++k)
    if (!std::isfinite(p.v[k].x) || !std::isfinite(p.v[k].y) || !std::isfinite(p.v[k].z)) return "non-finite vertex";
  int sum = 0;
  for (int f = 0; f < p.faces; ++f) sum += p.face_start[f + 1] - p.face_start[f];
  if (sum % 2 || p.n - sum / 2 + p.faces != 2) return "Euler characteristic is not 2";
  // Signed distance to a face's plane, >= 0 inside, computed on coordinates scaled by a power of two
  // near 1 / max |coordinate| (exact), so that nothing underflows or overflows at 1e-100 or 1e100.
  double m = 0;
  for (const Tet* t : {&a, &b})
    for (Point3 c : *t) m = std::max({m, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  int e;
  std::frexp(m, &e);
  auto down = [e](Point3 c) { return Point3{std::ldexp(c.x, -e), std::ldexp(c.y, -e), std::ldexp(c.z, -e)}; };
  auto distance = [&](const Tet& t, int face, Point3 v) {
    Point3 u[4] = {down(t[0]), down(t[1]), down(t[2]), down(t[3])};
    const Point3 q = u[(face + 1) % 4], r = u[(face + 2) % 4], s = u[(face + 3) % 4];
    // the exact volume over the area: thin faces of slivers have normals far too inexact for n . (v - q);
    // the area from the two shorter edges (the cross product of the long ones cancels)
    const Point3 edge[3] = {r - q, s - r, q - s};
    int longest = 0;
    for (int i = 1; i < 3; ++i)
      if (dot(edge[i], edge[i]) > dot(edge[longest], edge[longest])) longest = i;
    Point3 n = cross(edge[(longest + 1) % 3], edge[(longest + 2) % 3]);
    const double len = std::sqrt(dot(n, n));
    // a face whose three corners are collinear to within round-off has no well-defined plane to measure
    // against (its area is below 1e-12 of its longest edge squared): no check
    if (!(len > 1e-12 * dot(edge[longest], edge[longest]))) return 0.0;
    const double d = 6 * ref::exact_tet_volume(q, r, s, down(v)) / len;
    return std::ldexp(ref::exact_orientation3d(q, r, s, u[face]) > 0 ? d : -d, e);
  };
  for (int k = 0; k < p.n; ++k)
    for (int f = 0; f < 4; ++f) {
      if (distance(a, f, p.v[k]) < -tol) return "vertex outside a";
      if (distance(b, f, p.v[k]) < -tol) return "vertex outside b";
      if ((p.planes[k] >> f & 1) && std::fabs(distance(a, f, p.v[k])) > tol) return "vertex off its plane of a";
      if ((p.planes[k] >> (4 + f) & 1) && std::fabs(distance(b, f, p.v[k])) > tol) return "vertex off its plane of b";
    }
  return "";
}

}  // namespace dlmfsi::test3d

#include <random>
#include <vector>

#include "coupling/coupling3d.hpp"
#include "sparse/csr_matrix.hpp"
#include "errors.hpp"
#include "mesh/mesh3d.hpp"

namespace dlmfsi::test3d {

// n x m x l grid of cubes on the box [o, o + size], each cube split into the six Kuhn tetrahedra (the
// same diagonal in every cube: a conforming mesh); interior vertices moved at random by jitter times the
// cell size when jitter > 0, the amplitude halved (the same draws) until no tetrahedron turns over: a valid
// mesh (a turned tetrahedron would overlap its neighbours).
inline Mesh3 box_mesh(int n, int m, int l, Point3 o, Point3 size, double jitter = 0, unsigned seed = 1) {
  Mesh3 mesh;
  for (int k = 0; k <= l; ++k)
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.vertices.push_back({o.x + size.x * i / n, o.y + size.y * j / m, o.z + size.z * k / l});
  auto id = [&](int i, int j, int k) { return (k * (m + 1) + j) * (n + 1) + i; };
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < l; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (orient3d(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]) < 0)
            std::swap(t[2], t[3]);
          mesh.tetrahedra.push_back(t);
        }
  if (jitter > 0) {
    const std::vector<Point3> grid = mesh.vertices;
    const Point3 h{size.x / n, size.y / m, size.z / l};
    for (double amp = jitter;; amp /= 2) {
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> u(-1, 1);
      for (int k = 0; k <= l; ++k)
        for (int j = 0; j <= m; ++j)
          for (int i = 0; i <= n; ++i) {
            Point3& p = mesh.vertices[id(i, j, k)];
            p = grid[id(i, j, k)];
            if (i > 0 && i < n && j > 0 && j < m && k > 0 && k < l)
              p = p + Point3{amp * h.x * u(rng), amp * h.y * u(rng), amp * h.z * u(rng)};
          }
      bool positive = true;
      for (const auto& t : mesh.tetrahedra)
        positive = positive && orient3d(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]) > 0;
      if (positive || amp == 0) break;  // (at 0 the grid itself)
    }
  }
  mesh.build_adjacency();
  return mesh;
}

// A fluid box mesh with the tetrahedra whose centroid lies in a ball removed (a hole: non-convex).
inline Mesh3 with_hole(const Mesh3& mesh, Point3 centre, double radius) {
  Mesh3 out;
  out.vertices = mesh.vertices;
  for (int k = 0; k < mesh.size(); ++k) {
    Point3 c[4];
    mesh.corners(k, c);
    const Point3 m = 0.25 * (c[0] + c[1] + c[2] + c[3]) - centre;
    if (dot(m, m) > radius * radius) out.tetrahedra.push_back(mesh.tetrahedra[k]);
  }
  out.build_adjacency();
  return out;
}

// The mesh moved by x -> centre + R (x - centre) + shift (R a rotation about axis by angle, Rodrigues);
// angle 0 keeps the vertices bit for bit (then only the shift is applied, exactly for dyadic values).
inline Mesh3 moved(Mesh3 mesh, Point3 axis, double angle, Point3 centre, Point3 shift) {
  const double len = std::sqrt(dot(axis, axis));
  axis = (1 / len) * axis;
  const double c = std::cos(angle), s = std::sin(angle);
  for (Point3& p : mesh.vertices) {
    if (angle != 0) {
      const Point3 d = p - centre;
      p = centre + (c * d + s * cross(axis, d) + ((1 - c) * dot(axis, d)) * axis);
    }
    p = p + shift;
  }
  mesh.build_adjacency();
  return mesh;
}

// Rotation by a quarter turn about the z axis through centre, exact for dyadic coordinates.
inline Mesh3 quarter_turn(Mesh3 mesh, Point3 centre) {
  for (Point3& p : mesh.vertices) {
    const Point3 d = p - centre;
    p = centre + Point3{-d.y, d.x, d.z};
  }
  mesh.build_adjacency();
  return mesh;
}

}  // namespace dlmfsi::test3d

#include <map>

#include "fe/basis.hpp"
#include "map/mapped_element3d.hpp"

namespace dlmfsi::test3d {

// d xi / d x of tetrahedron k (rows: the gradients of the reference coordinates), independent of the core.
inline void reference_gradients(const Mesh3& m, int k, Point3 g[3]) {
  Point3 p[4];
  m.corners(k, p);
  const Point3 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0];
  const double det = dot(e1, cross(e2, e3));
  g[0] = (1 / det) * cross(e2, e3);
  g[1] = (1 / det) * cross(e3, e1);
  g[2] = (1 / det) * cross(e1, e2);
}

// Barycentric coordinates at reference point xi and their physical gradients.
inline void barycentric(const Mesh3& m, int k, Point3 xi, double l[4], Point3 g[4]) {
  Point3 r[3];
  reference_gradients(m, k, r);
  l[0] = 1 - xi.x - xi.y - xi.z;
  l[1] = xi.x;
  l[2] = xi.y;
  l[3] = xi.z;
  g[1] = r[0];
  g[2] = r[1];
  g[3] = r[2];
  g[0] = -1.0 * (r[0] + r[1] + r[2]);
}

// Scalar P1 Lagrange on a tetrahedral mesh (dofs: vertices), written independently of the adapter.
class P1Tet : public Basis3 {
 public:
  explicit P1Tet(const Mesh3& m) : m_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return static_cast<int>(m_.vertices.size()); }
  int local_dofs() const override { return 4; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 4; }
  void dofs(int k, int* g) const override {
    for (int i = 0; i < 4; ++i) g[i] = m_.tetrahedra[k][i];
  }
  void evaluate(int k, Point3 xi, double* out) const override {
    double l[4];
    Point3 g[4];
    barycentric(m_, k, xi, l, g);
    for (int i = 0; i < 4; ++i) {
      out[4 * i] = l[i];
      out[4 * i + 1] = g[i].x;
      out[4 * i + 2] = g[i].y;
      out[4 * i + 3] = g[i].z;
    }
  }
  Point3 node(int dof) const { return m_.vertices[dof]; }

 private:
  const Mesh3& m_;
};

// Scalar P2 Lagrange: vertex dofs lambda_i (2 lambda_i - 1), then edge dofs 4 lambda_i lambda_j on the
// edges (0,1), (0,2), (0,3), (1,2), (1,3), (2,3); global dofs: the vertices, then the mesh's edges.
class P2Tet : public Basis3 {
 public:
  explicit P2Tet(const Mesh3& m) : m_(m) {
    static const int e[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    std::map<std::pair<int, int>, int> id;
    edge_dofs_.resize(m.tetrahedra.size());
    for (size_t k = 0; k < m.tetrahedra.size(); ++k)
      for (int i = 0; i < 6; ++i) {
        int a = m.tetrahedra[k][e[i][0]], b = m.tetrahedra[k][e[i][1]];
        if (a > b) std::swap(a, b);
        auto it = id.find({a, b});
        if (it == id.end()) {
          it = id.insert({{a, b}, static_cast<int>(m.vertices.size() + nodes_.size())}).first;
          nodes_.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
        }
        edge_dofs_[k][i] = it->second;
      }
  }
  int components() const override { return 1; }
  int dof_count() const override { return static_cast<int>(m_.vertices.size() + nodes_.size()); }
  int local_dofs() const override { return 10; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 10; }
  void dofs(int k, int* g) const override {
    for (int i = 0; i < 4; ++i) g[i] = m_.tetrahedra[k][i];
    for (int i = 0; i < 6; ++i) g[4 + i] = edge_dofs_[k][i];
  }
  void evaluate(int k, Point3 xi, double* out) const override {
    static const int e[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    double l[4];
    Point3 g[4];
    barycentric(m_, k, xi, l, g);
    auto put = [out](int df, double v, Point3 d) {
      out[4 * df] = v;
      out[4 * df + 1] = d.x;
      out[4 * df + 2] = d.y;
      out[4 * df + 3] = d.z;
    };
    for (int i = 0; i < 4; ++i) put(i, l[i] * (2 * l[i] - 1), (4 * l[i] - 1) * g[i]);
    for (int i = 0; i < 6; ++i) {
      const int a = e[i][0], b = e[i][1];
      put(4 + i, 4 * l[a] * l[b], 4 * l[b] * g[a] + 4 * l[a] * g[b]);
    }
  }
  Point3 node(int dof) const {
    const int nv = static_cast<int>(m_.vertices.size());
    return dof < nv ? m_.vertices[dof] : nodes_[dof - nv];
  }

 private:
  const Mesh3& m_;
  std::vector<std::array<int, 6>> edge_dofs_;
  std::vector<Point3> nodes_;
};

// Three P1 components (a velocity-like vector space): component c on local dofs [4c, 4c + 4), global dof
// c * vertices + vertex.
class VectorP1Tet : public Basis3 {
 public:
  explicit VectorP1Tet(const Mesh3& m) : m_(m), scalar_(m) {}
  int components() const override { return 3; }
  int dof_count() const override { return 3 * static_cast<int>(m_.vertices.size()); }
  int local_dofs() const override { return 12; }
  void component_dofs(int c, int& f, int& l) const override {
    f = 4 * c;
    l = 4 * c + 4;
  }
  void dofs(int k, int* g) const override {
    const int nv = static_cast<int>(m_.vertices.size());
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 4; ++i) g[4 * c + i] = c * nv + m_.tetrahedra[k][i];
  }
  void evaluate(int k, Point3 xi, double* out) const override {
    double s[16];
    scalar_.evaluate(k, xi, s);
    std::fill(out, out + 12 * 3 * 4, 0.0);
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 4; ++d) out[((4 * c + i) * 3 + c) * 4 + d] = s[4 * i + d];
  }

 private:
  const Mesh3& m_;
  P1Tet scalar_;
};

// X(s) = A s + b with s the solid's coordinates.
class AffineMap3 : public SolidMap3 {
 public:
  AffineMap3(const Mesh3& solid, const double a[3][3], Point3 b) : solid_(solid), b_(b) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a_[i][j] = a[i][j];
  }
  Point3 apply(Point3 s) const {
    return Point3{a_[0][0] * s.x + a_[0][1] * s.y + a_[0][2] * s.z, a_[1][0] * s.x + a_[1][1] * s.y + a_[1][2] * s.z,
                  a_[2][0] * s.x + a_[2][1] * s.y + a_[2][2] * s.z} +
           b_;
  }
  MapValue3 evaluate(int k, Point3 xi) const override {
    Point3 p[4];
    solid_.corners(k, p);
    MapValue3 v;
    v.x = apply(from_reference(p, xi));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) v.jac[i][j] = a_[i][j];
    return v;
  }
  int degree() const override { return 1; }

 private:
  const Mesh3& solid_;
  double a_[3][3];
  Point3 b_;
};

// A rotation by angle about axis (Rodrigues), times a shear that keeps volumes when shear_volume.
inline void rotation(Point3 axis, double angle, double r[3][3]) {
  const double len = std::sqrt(dot(axis, axis));
  axis = (1 / len) * axis;
  const double c = std::cos(angle), s = std::sin(angle), u[3] = {axis.x, axis.y, axis.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = (1 - c) * u[i] * u[j] + (i == j ? c : 0);
  r[0][1] -= s * u[2];
  r[0][2] += s * u[1];
  r[1][0] += s * u[2];
  r[1][2] -= s * u[0];
  r[2][0] -= s * u[1];
  r[2][1] += s * u[0];
}

// l' B u for a compressed-row matrix B.
inline double bilinear(const CsrMatrix& b, const std::vector<double>& l, const std::vector<double>& u) {
  double s = 0;
  for (int i = 0; i < b.rows; ++i)
    for (int e = b.start[i]; e < b.start[i + 1]; ++e) s += l[i] * b.value[e] * u[b.column[e]];
  return s;
}

// The error message of assembling P1 x P1 on the two meshes under the map ("" when it assembles);
// drop: the solid's part outside the fluid mesh dropped rather than an error.
inline std::string coupling_error(const Mesh3& fluid, const Mesh3& solid, const SolidMap3& map, bool drop = false,
                                  CouplingReport* report = nullptr) {
  const P1Tet f(fluid), s(solid);
  try {
    CouplingOptions opt;
    opt.drop_outside = drop;
    assemble_coupling(FluidSide3(fluid, f, {0}), SolidSide3(solid, s, {0}), map, opt, report);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace dlmfsi::test3d
