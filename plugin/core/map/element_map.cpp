#include "map/element_map.hpp"

#include <cmath>
#include <cstdio>

#include "errors.hpp"
#include "map/polynomial_map.hpp"

namespace dlmfsi {

// Not inlined into fit, whose code stays short for the maps that give their coefficients (FieldMap).
__attribute__((noinline)) void TriangleMap::fit_on_lattice(const SolidMap& map, double* cx, double* cy) const {
  const int n = monomial_count(degree_);
  double vx[monomial_count(kMaxDegree)] = {}, vy[monomial_count(kMaxDegree)] = {};
  for (int p = 0; p < n; ++p) {
    const Point x = map.evaluate(k, lattice_point(degree_, p)).x;
    vx[p] = x.x;
    vy[p] = x.y;
  }
  // relative to the first lattice point's value (V^-1's rows add up to e_0, constants being fitted exactly),
  // so that the non-constant coefficients keep the digits of the triangle's size
  const auto& inv = vandermonde_inverse(degree_);
  for (int m = 0; m < n; ++m) {
    cx[m] = cy[m] = 0;
    for (int p = 1; p < n; ++p) {
      cx[m] += inv[m * n + p] * (vx[p] - vx[0]);
      cy[m] += inv[m * n + p] * (vy[p] - vy[0]);
    }
  }
  cx[0] += vx[0];
  cy[0] += vy[0];
}

void TriangleMap::fit(const Mesh& solid_mesh, const SolidMap& map, int kk) {
  k = kk;
  map_ = &map;
  solid_mesh.corners(k, solid);
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  const double ds = cross(e1, e2);
  if (!(ds > 0)) throw Error(name() + " is degenerate or clockwise in the solid mesh");
  // Products of the multiplier's gradients (1/h each) and of the area (h^2) stay normal numbers.
  if (ds < 0x1p-1010 || ds > 0x1p1010) {
    char s[160];
    std::snprintf(s, sizeof s, " has area %.3g: solid triangles from about 1e-150 to 1e150 in size are supported", 0.5 * ds);
    throw Error(name() + s);
  }
  inv_[0][0] = e2.y / ds;
  inv_[0][1] = -e2.x / ds;
  inv_[1][0] = -e1.y / ds;
  inv_[1][1] = e1.x / ds;

  degree_ = map.degree();
  if (degree_ > kMaxDegree) degree_ = -1;
  if (degree_ < 1) return;
  // c = V^-1 (X at the lattice points), V the lattice's Vandermonde matrix, unless the map gives c.
  const int n = monomial_count(degree_);
  double cx[monomial_count(kMaxDegree)], cy[monomial_count(kMaxDegree)];
  if (!map.coefficients(k, cx, cy)) fit_on_lattice(map, cx, cy);
  // c * 0 is 0 for a finite c, NaN for NaN or Inf: the sum of those terms is 0 when every coefficient is finite.
  double finite = 0;
  if (n == 3)  // degree 1: the loop written out
    finite = cx[0] * 0 + cy[0] * 0 + cx[1] * 0 + cy[1] * 0 + cx[2] * 0 + cy[2] * 0;
  else
    for (int m = 0; m < n; ++m) finite += cx[m] * 0 + cy[m] * 0;
  if (finite != 0) throw Error("the map is NaN or Inf in " + name());
  // Monomial 0 is the constant: X(0, 0). Kept apart, so that X - X(0, 0) is evaluated to the precision of the
  // other terms (a triangle of size h at distance R from 0: relative eps, not eps R / h).
  origin_ = {cx[0], cy[0]};
  cx[0] = cy[0] = 0;
  c_.set(degree_, cx, cy);
}

void TriangleMap::displacement(Point xi, Point& x, Point& dx1, Point& dx2) const {
  switch (degree_) {
    case 1: evaluate_polynomial<1>(c_, xi, x, dx1, dx2); break;
    case 2: evaluate_polynomial<2>(c_, xi, x, dx1, dx2); break;
    case 3: evaluate_polynomial<3>(c_, xi, x, dx1, dx2); break;
    case 4: evaluate_polynomial<4>(c_, xi, x, dx1, dx2); break;
    case 5: evaluate_polynomial<5>(c_, xi, x, dx1, dx2); break;
    default: evaluate_polynomial<6>(c_, xi, x, dx1, dx2); break;  // fitted(): degree_ <= kMaxDegree
  }
}

void TriangleMap::polynomial_points(int n, const double* xi1, const double* xi2, double* x, double* y, double* a0,
                                    double* a1, double* b0, double* b1) const {
  displacement_points(n, xi1, xi2, x, y, a0, a1, b0, b1);
  for (int q = 0; q < n; ++q) {
    x[q] += origin_.x;
    y[q] += origin_.y;
  }
}

void TriangleMap::displacement_points(int n, const double* xi1, const double* xi2, double* x, double* y, double* a0,
                                      double* a1, double* b0, double* b1) const {
  switch (degree_) {
    case 1: evaluate_polynomial_points<1>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
    case 2: evaluate_polynomial_points<2>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
    case 3: evaluate_polynomial_points<3>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
    case 4: evaluate_polynomial_points<4>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
    case 5: evaluate_polynomial_points<5>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
    default: evaluate_polynomial_points<6>(c_, n, xi1, xi2, x, y, a0, a1, b0, b1); break;
  }
}

MapValue TriangleMap::at(Point xi) const {
  if (degree_ < 1) return map_->evaluate(k, xi);
  MapValue v;
  Point d1, d2;
  polynomial(xi, v.x, d1, d2);
  set_jacobian(d1, d2, v);
  return v;
}

void TriangleMap::reference_derivatives(Point xi, Point& x, Point& d1, Point& d2) const {
  if (degree_ >= 1) {
    polynomial(xi, x, d1, d2);
    return;
  }
  const MapValue v = map_->evaluate(k, xi);
  x = v.x;
  reference_jacobian(v, d1, d2);
}

}  // namespace dlmfsi
