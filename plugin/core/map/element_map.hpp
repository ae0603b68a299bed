// X on one solid triangle, in the triangle's reference coordinates xi: s = s0 + xi1 e1 + xi2 e2 with
// s0, s1, s2 the corners (counter-clockwise), e1 = s1 - s0, e2 = s2 - s0.
#pragma once
#include <string>

#include "fe/lattice.hpp"
#include "map/solid_map.hpp"
#include "mesh/mesh.hpp"
#include "map/polynomial_map.hpp"

namespace dlmfsi {

// When the map's degree d is known (1 to kMaxDegree), X is fitted once on the triangle's degree-d lattice
// (exact for a polynomial map: X = sum over the monomials m of c_m xi1^a xi2^b, lattice.hpp order) and then
// evaluated as that polynomial; otherwise every evaluation goes to the map.
class TriangleMap {
 public:
  static constexpr int kMaxDegree = kMaxPolynomialMapDegree;
  int k = -1;
  Point solid[3];  // corners in the reference configuration

  // Takes solid triangle k of the mesh and fits X on it. Throws Error naming the triangle when it is
  // degenerate or clockwise, outside the supported sizes, or when the fitted coefficients are NaN or Inf.
  void fit(const Mesh& solid_mesh, const SolidMap& map, int k);

  // Is X evaluated as the fitted polynomial?
  bool fitted() const { return degree_ >= 1; }
  int degree() const { return degree_; }

  // X at reference corner i: (0, 0), (1, 0), (0, 1): origin() + corner_displacement(i).
  Point corner_image(int i) const {
    if (degree_ < 1) {
      const Point ref[3] = {{0, 0}, {1, 0}, {0, 1}};
      return map_->evaluate(k, ref[i]).x;
    }
    return i == 0 ? origin_ : origin_ + corner_displacement(i);
  }
  // X(corner i) - X(corner 0) (fitted() only). There every monomial but the powers of one coordinate
  // vanishes: the sum of their coefficients (monomial xi1^(t-b) xi2^b is number t(t+1)/2 + b), the constant
  // term excluded, so that the sum carries the digits of the triangle's size, not of its distance from 0.
  Point corner_displacement(int i) const {
    Point x{0, 0};
    if (i == 0) return x;
    if (degree_ == 1) return x + Point{c_.x[2 * i], c_.x[2 * i + 1]};  // the loop's one term (t = 1, m = i)
    for (int t = 1; t <= degree_; ++t) {
      const int m = t * (t + 1) / 2 + (i == 2 ? t : 0);
      x = x + Point{c_.x[2 * m], c_.x[2 * m + 1]};
    }
    return x;
  }
  // X at reference corner 0 (fitted() only), the point displacements are measured from.
  Point origin() const { return origin_; }

  // X and its derivatives in the reference coordinates, d1 = dX/dxi1 and d2 = dX/dxi2, at xi.
  void reference_derivatives(Point xi, Point& x, Point& d1, Point& d2) const;

  // X and its jacobian (with respect to s) at reference point xi.
  MapValue at(Point xi) const;

  // The map itself (not the fit) at xi.
  MapValue evaluate(Point xi) const { return map_->evaluate(k, xi); }

  // The fitted polynomial's coefficients (fitted() only), its constant term 0: the coefficients of
  // X - origin().
  const PolynomialMapCoefficients& coefficients() const { return c_; }
  // The fitted polynomial and its derivatives in xi (fitted() only): x = origin() + displacement.
  void polynomial(Point xi, Point& x, Point& d1, Point& d2) const {
    displacement(xi, x, d1, d2);
    x = origin_ + x;
  }
  // X(xi) - origin() and the derivatives (fitted() only), to the relative precision of the triangle's image
  // wherever it lies.
  void displacement(Point xi, Point& x, Point& d1, Point& d2) const;
  // The displacement at n points, as arrays (evaluate_polynomial_points: x, y = X - origin(); a0, a1 = d1;
  // b0, b1 = d2).
  void displacement_points(int n, const double* xi1, const double* xi2, double* x, double* y, double* a0,
                           double* a1, double* b0, double* b1) const;
  // The same with x, y = X.
  void polynomial_points(int n, const double* xi1, const double* xi2, double* x, double* y, double* a0, double* a1,
                         double* b0, double* b1) const;

  // d1 = dX/dxi1 = dX/ds e1 and d2 = dX/dxi2 = dX/ds e2 from v.jac = dX/ds.
  void reference_jacobian(const MapValue& v, Point& d1, Point& d2) const {
    const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
    d1 = {v.jac[0][0] * e1.x + v.jac[0][1] * e1.y, v.jac[1][0] * e1.x + v.jac[1][1] * e1.y};
    d2 = {v.jac[0][0] * e2.x + v.jac[0][1] * e2.y, v.jac[1][0] * e2.x + v.jac[1][1] * e2.y};
  }

  // v.jac = dX/ds = dX/dxi (ds/dxi)^-1 from d1 = dX/dxi1, d2 = dX/dxi2.
  void set_jacobian(Point d1, Point d2, MapValue& v) const {
    v.jac[0][0] = d1.x * inv_[0][0] + d2.x * inv_[1][0];
    v.jac[0][1] = d1.x * inv_[0][1] + d2.x * inv_[1][1];
    v.jac[1][0] = d1.y * inv_[0][0] + d2.y * inv_[1][0];
    v.jac[1][1] = d1.y * inv_[0][1] + d2.y * inv_[1][1];
  }

  // "solid triangle k", for error messages.
  std::string name() const { return "solid triangle " + std::to_string(k); }

 private:
  // cx, cy = V^-1 (X at the degree-d lattice points), V the lattice's Vandermonde matrix (d = degree()).
  void fit_on_lattice(const SolidMap& map, double* cx, double* cy) const;
  const SolidMap* map_ = nullptr;
  int degree_ = -1;
  Point origin_{0, 0};           // X at reference corner 0: the constant term of the fit
  PolynomialMapCoefficients c_;  // monomial coefficients of X - origin_, Y and of their derivatives
  double inv_[2][2];                                                        // (d s / d xi)^-1
};

}  // namespace dlmfsi
