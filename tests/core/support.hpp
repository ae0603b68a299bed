// Test helpers: structured meshes and a P1 Lagrange basis written independently of the adapter.
#pragma once
#include <cmath>
#include <random>

#include "fe/basis.hpp"
#include "map/solid_map.hpp"
#include "mesh/mesh.hpp"

namespace dlmfsi::test {

// n x m grid on [x0, x0 + w] x [y0, y0 + h], each cell split by a diagonal (alternating when alternate).
inline Mesh grid_mesh(int n, int m, double x0, double y0, double w, double h, bool alternate = false) {
  Mesh mesh;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) mesh.vertices.push_back({x0 + w * i / n, y0 + h * j / m});
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      if (alternate && (i + j) % 2) {
        mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        mesh.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  mesh.build_adjacency();
  return mesh;
}

// Scalar P1 Lagrange on a mesh: dofs are vertices.
class P1 : public Basis {
 public:
  explicit P1(const Mesh& m) : m_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return static_cast<int>(m_.vertices.size()); }
  int local_dofs() const override { return 3; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 3; }
  void dofs(int k, int* g) const override {
    for (int i = 0; i < 3; ++i) g[i] = m_.triangles[k][i];
  }
  void evaluate(int k, Point xi, double* out) const override {
    Point p[3];
    m_.corners(k, p);
    const double det = cross(p[1] - p[0], p[2] - p[0]);
    // gradients of the barycentric coordinates
    const double g[3][2] = {{(p[1].y - p[2].y) / det, (p[2].x - p[1].x) / det},
                            {(p[2].y - p[0].y) / det, (p[0].x - p[2].x) / det},
                            {(p[0].y - p[1].y) / det, (p[1].x - p[0].x) / det}};
    const double l[3] = {1 - xi.x - xi.y, xi.x, xi.y};
    for (int i = 0; i < 3; ++i) {
      out[3 * i] = l[i];
      out[3 * i + 1] = g[i][0];
      out[3 * i + 2] = g[i][1];
    }
  }
  // The barycentric coordinates alone (as the FreeFEM adapter's spaces give values without derivatives).
  void values(int, Point xi, double* out) const override {
    out[0] = 1 - xi.x - xi.y;
    out[3] = xi.x;
    out[6] = xi.y;
  }

 private:
  const Mesh& m_;
};

// [P1, P1] on a mesh: local dofs 0-2 carry component 0 and 3-5 component 1 (FreeFEM's order), global dof
// 2 v + c; component 1's functions are scale times component 0's.
class VectorP1 : public Basis {
 public:
  explicit VectorP1(const Mesh& m, double scale = 1) : p1_(m), m_(m), scale_(scale) {}
  int components() const override { return 2; }
  int dof_count() const override { return 2 * static_cast<int>(m_.vertices.size()); }
  int local_dofs() const override { return 6; }
  void component_dofs(int c, int& f, int& l) const override {
    f = 3 * c;
    l = 3 * c + 3;
  }
  void dofs(int k, int* g) const override {
    for (int c = 0; c < 2; ++c)
      for (int i = 0; i < 3; ++i) g[3 * c + i] = 2 * m_.triangles[k][i] + c;
  }
  void evaluate(int k, Point xi, double* out) const override {
    double scalar[9];
    p1_.evaluate(k, xi, scalar);
    for (int df = 0; df < 6; ++df)
      for (int c = 0; c < 2; ++c)
        for (int d = 0; d < 3; ++d)
          out[(df * 2 + c) * 3 + d] = df / 3 == c ? (c == 1 ? scale_ : 1) * scalar[(df % 3) * 3 + d] : 0;
  }

 private:
  P1 p1_;
  const Mesh& m_;
  double scale_;
};

// An affine map X(s) = A s + b given on the solid mesh.
class AffineMap : public SolidMap {
 public:
  AffineMap(const Mesh& solid, double a00, double a01, double a10, double a11, double b0, double b1)
      : solid_(solid), a_{{a00, a01}, {a10, a11}}, b_{b0, b1} {}
  MapValue evaluate(int k, Point xi) const override {
    Point c[3];
    solid_.corners(k, c);
    const Point s = from_reference(c, xi);
    MapValue v;
    v.x = {a_[0][0] * s.x + a_[0][1] * s.y + b_.x, a_[1][0] * s.x + a_[1][1] * s.y + b_.y};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) v.jac[i][j] = a_[i][j];
    return v;
  }

 private:
  const Mesh& solid_;
  double a_[2][2];
  Point b_;
};

}  // namespace dlmfsi::test
