#include "map.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "errors.hpp"
#include "predicates.hpp"

namespace dlmfsi {

FieldMap::FieldMap(const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y, const double* coef_y,
                   int comp_y) {
  part_[0] = {&space_x, coef_x, comp_x, 0, 0};
  part_[1] = {&space_y, coef_y, comp_y, 0, 0};
  bool known = true;
  degree_ = 0;
  for (auto& p : part_) {
    if (p.comp < 0 || p.comp >= p.space->components()) throw Error("map component out of range");
    p.space->component_dofs(p.comp, p.first, p.last);
    const int d = polynomial_degree(*p.space, {p.comp});
    if (d < 0) known = false;
    degree_ = std::max(degree_, d);
  }
  if (!known || degree_ < 1) degree_ = -1;  // not polynomial (or constant): evaluate the map itself
}

void FieldMap::add(const Part& p, int k, Point xi, int a, MapValue& v) const {
  const int nd = p.space->local_dofs(), nc = p.space->components();
  // Small fixed buffers cover every FreeFEM 2D element used for maps; larger ones fall back to the heap.
  double stack_out[64 * 4 * 3];
  int stack_dofs[64];
  std::vector<double> heap_out;
  std::vector<int> heap_dofs;
  double* out = stack_out;
  int* dofs = stack_dofs;
  if (nd * nc * 3 > 64 * 4 * 3 || nd > 64) {
    heap_out.resize(static_cast<size_t>(nd) * nc * 3);
    heap_dofs.resize(nd);
    out = heap_out.data();
    dofs = heap_dofs.data();
  }
  p.space->evaluate(k, xi, out);
  p.space->dofs(k, dofs);
  double val = 0, dx = 0, dy = 0;
  for (int df = p.first; df < p.last; ++df) {
    const double c = p.coef[dofs[df]];
    const double* f = out + (df * nc + p.comp) * 3;
    val += c * f[0];
    dx += c * f[1];
    dy += c * f[2];
  }
  (a == 0 ? v.x.x : v.x.y) = val;
  v.jac[a][0] = dx;
  v.jac[a][1] = dy;
}

MapValue FieldMap::evaluate(int k, Point xi) const {
  MapValue v{};
  add(part_[0], k, xi, 0, v);
  add(part_[1], k, xi, 1, v);
  return v;
}

namespace {

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::string name(int k) { return "solid triangle " + std::to_string(k); }

constexpr int monomials(int d) { return (d + 1) * (d + 2) / 2; }

// Monomial m is xi1^a xi2^b, listed by total degree t = a + b, then b = 0..t.
void exponents(int m, int& a, int& b) {
  int t = 0;
  while (monomials(t) <= m) ++t;
  b = m - monomials(t - 1);
  a = t - b;
}

// Lattice point m of degree d: (a/d, b/d) with the exponents of monomial m.
Point lattice(int d, int m) {
  int a, b;
  exponents(m, a, b);
  return {static_cast<double>(a) / d, static_cast<double>(b) / d};
}

// Inverse of the Vandermonde matrix V[p][m] = xi1^a_m xi2^b_m at the lattice points p of degree d.
const std::vector<double>& vandermonde_inverse(int d) {
  static const auto table = [] {
    std::vector<std::vector<double>> inv(MappedTriangle::kMaxDegree + 1);
    for (int deg = 1; deg <= MappedTriangle::kMaxDegree; ++deg) {
      const int n = monomials(deg);
      std::vector<double> a(static_cast<size_t>(n) * 2 * n, 0.0);  // [V | I], Gauss-Jordan with pivoting
      for (int p = 0; p < n; ++p) {
        const Point x = lattice(deg, p);
        for (int m = 0; m < n; ++m) {
          int ea, eb;
          exponents(m, ea, eb);
          a[p * 2 * n + m] = std::pow(x.x, ea) * std::pow(x.y, eb);
        }
        a[p * 2 * n + n + p] = 1;
      }
      for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
          if (std::fabs(a[r * 2 * n + c]) > std::fabs(a[piv * 2 * n + c])) piv = r;
        for (int j = 0; j < 2 * n; ++j) std::swap(a[c * 2 * n + j], a[piv * 2 * n + j]);
        const double diag = a[c * 2 * n + c];
        for (int j = 0; j < 2 * n; ++j) a[c * 2 * n + j] /= diag;
        for (int r = 0; r < n; ++r)
          if (r != c) {
            const double f = a[r * 2 * n + c];
            if (f != 0)
              for (int j = 0; j < 2 * n; ++j) a[r * 2 * n + j] -= f * a[c * 2 * n + j];
          }
      }
      inv[deg].resize(static_cast<size_t>(n) * n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) inv[deg][r * n + c] = a[r * 2 * n + n + c];
    }
    return inv;
  }();
  return table[d];
}

}  // namespace

void MappedTriangle::polynomial(Point xi, Point& x, Point& dx1, Point& dx2) const {
  double p1[kMaxDegree + 1], p2[kMaxDegree + 1];
  p1[0] = p2[0] = 1;
  for (int i = 1; i <= degree_; ++i) {
    p1[i] = p1[i - 1] * xi.x;
    p2[i] = p2[i - 1] * xi.y;
  }
  x = dx1 = dx2 = {0, 0};
  int m = 0;
  for (int t = 0; t <= degree_; ++t)
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b;
      const double v = p1[a] * p2[b];
      x = x + Point{cx_[m] * v, cy_[m] * v};
      if (a > 0) {
        const double d = a * p1[a - 1] * p2[b];
        dx1 = dx1 + Point{cx_[m] * d, cy_[m] * d};
      }
      if (b > 0) {
        const double d = b * p1[a] * p2[b - 1];
        dx2 = dx2 + Point{cx_[m] * d, cy_[m] * d};
      }
    }
}

MapValue MappedTriangle::at(Point xi) const {
  if (degree_ < 1) return map_->evaluate(k, xi);
  MapValue v;
  Point d1, d2;
  polynomial(xi, v.x, d1, d2);
  // dX/ds = dX/dxi (ds/dxi)^-1
  v.jac[0][0] = d1.x * inv_[0][0] + d2.x * inv_[1][0];
  v.jac[0][1] = d1.x * inv_[0][1] + d2.x * inv_[1][1];
  v.jac[1][0] = d1.y * inv_[0][0] + d2.y * inv_[1][0];
  v.jac[1][1] = d1.y * inv_[0][1] + d2.y * inv_[1][1];
  return v;
}

void MappedTriangle::prepare(const Mesh& solid_mesh, const SolidMap& map, int kk) {
  k = kk;
  map_ = &map;
  solid_mesh.corners(k, solid);
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  const double ds = cross(e1, e2);
  if (!(ds > 0)) throw Error(name(k) + " is degenerate or clockwise in the solid mesh");
  inv_[0][0] = e2.y / ds;
  inv_[0][1] = -e2.x / ds;
  inv_[1][0] = -e1.y / ds;
  inv_[1][1] = e1.x / ds;

  degree_ = map.degree();
  if (degree_ > kMaxDegree) degree_ = -1;
  if (degree_ >= 1) {
    const int n = monomials(degree_);
    double vx[monomials(kMaxDegree)], vy[monomials(kMaxDegree)];
    for (int p = 0; p < n; ++p) {
      const Point x = map.evaluate(k, lattice(degree_, p)).x;
      if (!finite(x)) throw Error("the map is NaN or Inf in " + name(k));
      vx[p] = x.x;
      vy[p] = x.y;
    }
    const auto& inv = vandermonde_inverse(degree_);
    for (int m = 0; m < n; ++m) {
      cx_[m] = cy_[m] = 0;
      for (int p = 0; p < n; ++p) {
        cx_[m] += inv[m * n + p] * vx[p];
        cy_[m] += inv[m * n + p] * vy[p];
      }
    }
  }
  const Point ref[3] = {{0, 0}, {1, 0}, {0, 1}};
  for (int i = 0; i < 3; ++i) {
    image[i] = degree_ >= 1 ? map.evaluate(k, ref[i]).x : at(ref[i]).x;
    if (!finite(image[i])) throw Error("the map is NaN or Inf at a corner of " + name(k));
  }
  const int o = orient2d(image[0], image[1], image[2]);
  if (o == 0) throw Error("the map flattens " + name(k) + " (its image has zero area)");
  if (o < 0) throw Error("the map inverts " + name(k) + " (its image is clockwise: a reflection or a fold)");

  // Compare X with the affine interpolant of the corner images at edge and interior points.
  const double scale = std::fabs(image[1].x - image[0].x) + std::fabs(image[1].y - image[0].y) +
                       std::fabs(image[2].x - image[0].x) + std::fabs(image[2].y - image[0].y);
  const double tol = 1e-13 * scale;
  const Point edge_points[6] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}, {0.25, 0}, {0.75, 0.25}, {0, 0.75}};
  const Point inner_points[3] = {{1.0 / 3, 1.0 / 3}, {0.2, 0.6}, {0.6, 0.15}};
  straight = true;
  affine = true;
  for (int e = 0; e < 6; ++e) {
    const Point x = at(edge_points[e]).x;
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point line = from_reference(image, edge_points[e]);
    // Straight edge: the image point lies on the chord through the corner images (a parametrisation along
    // the chord that is not uniform is allowed).
    const Point a = image[e % 3], b = image[(e + 1) % 3];
    const Point ab = b - a;
    const double off = std::fabs(cross(ab, x - a)) / std::sqrt(ab.x * ab.x + ab.y * ab.y);
    if (off > tol) straight = false;
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) affine = false;
  }
  for (const Point& p : inner_points) {
    const Point x = at(p).x;
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point line = from_reference(image, p);
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) affine = false;
  }
  if (affine) {
    // dX/ds = [image edges] [solid edges]^-1
    const Point f1 = image[1] - image[0], f2 = image[2] - image[0];
    affine_value.x = image[0];
    affine_value.jac[0][0] = (f1.x * e2.y - f2.x * e1.y) / ds;
    affine_value.jac[0][1] = (f2.x * e1.x - f1.x * e2.x) / ds;
    affine_value.jac[1][0] = (f1.y * e2.y - f2.y * e1.y) / ds;
    affine_value.jac[1][1] = (f2.y * e1.x - f1.y * e2.x) / ds;
    affine_det = det2(affine_value.jac);
    if (!(affine_det > 0)) throw Error("the map flattens " + name(k));
  }
}

Point MappedTriangle::pull_back(Point y, MapValue& value) const {
  Point xi = to_reference(image, y);
  if (affine) {
    value = affine_value;
    value.x = y;
    return xi;
  }
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  double previous = 1e300;
  for (int it = 0; it < 40; ++it) {
    value = at(xi);
    // d X / d xi = jac * [e1 e2]
    const double a = value.jac[0][0] * e1.x + value.jac[0][1] * e1.y, b = value.jac[0][0] * e2.x + value.jac[0][1] * e2.y;
    const double c = value.jac[1][0] * e1.x + value.jac[1][1] * e1.y, d = value.jac[1][0] * e2.x + value.jac[1][1] * e2.y;
    const double det = a * d - b * c;
    if (!(det > 0)) throw Error("the map folds " + name(k) + " (jacobian determinant " + std::to_string(det) + ")");
    const Point r = y - value.x;
    const Point step{(d * r.x - b * r.y) / det, (a * r.y - c * r.x) / det};
    xi = xi + step;
    const double size = std::fabs(step.x) + std::fabs(step.y);
    // Converged, or stalled at the round-off floor (quadratic convergence would have halved the step).
    if (size < 1e-14 || (size < 1e-10 && size > 0.5 * previous)) {
      value = at(xi);
      return xi;
    }
    previous = size;
  }
  throw Error("Newton's method did not converge pulling a point back into " + name(k));
}

}  // namespace dlmfsi
