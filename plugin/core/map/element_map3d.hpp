// X on one solid tetrahedron, in the tetrahedron's reference coordinates xi: s = s0 + xi1 e1 + xi2 e2 + xi3 e3
// with e_i = s_i - s0 (the counterpart of element_map.hpp's TriangleMap).
#pragma once
#include <string>

#include "fe/lattice3d.hpp"
#include "map/solid_map3d.hpp"
#include "mesh/mesh3d.hpp"

namespace dlmfsi {

// When the map's degree d is known (1 to kMaxDegree), X is fitted once on the tetrahedron's degree-d lattice
// (exact for a polynomial map) and then evaluated as that polynomial; otherwise every evaluation goes to the map.
class TetrahedronMap {
 public:
  static constexpr int kMaxDegree = kMaxMapDegree3;
  int k = -1;
  Point3 solid[4];  // corners in the reference configuration

  // Takes solid tetrahedron k of the mesh and fits X on it. Throws Error naming the tetrahedron when it is
  // flat or negatively oriented, outside the supported sizes, or when the fitted coefficients are NaN or Inf.
  void fit(const Mesh3& solid_mesh, const SolidMap3& map, int k);

  // X and its jacobian (with respect to s) at reference point xi.
  MapValue3 at(Point3 xi) const;
  // v.jac = dX/ds from the reference-coordinate derivatives d[i] = dX/dxi_i: dX/dxi (ds/dxi)^-1.
  void set_jacobian(const Point3 d[3], MapValue3& v) const;
  // d xi / d s_b: the reference-coordinate direction of the solid's axis b (0, 1, 2).
  Point3 reference_direction(int b) const { return {inv_[0][b], inv_[1][b], inv_[2][b]}; }
  // For a quadratic fit (fitted_degree() == 2): h[a][i][j] = d^2 X_a / dxi_i dxi_j, the same everywhere; true.
  // False for any other degree.
  bool reference_hessian(double h[3][3][3]) const;
  // The degree of the polynomial fitted to X (1 to kMaxDegree), or -1 when X is evaluated itself.
  int fitted_degree() const { return degree_; }
  // The monomial coefficients (lattice3d.hpp order) of component a of the fitted polynomial.
  const double* coefficients(int a) const { return c_[a]; }
  // X and its reference-coordinate derivatives d[i] = dX/dxi_i at xi (of the fitted polynomial, or of the
  // map itself when its degree is unknown).
  void reference_derivatives(Point3 xi, Point3& x, Point3 d[3]) const;
  // X at xi alone (the same value as reference_derivatives' x, bit for bit).
  Point3 position(Point3 xi) const;

  // A P1b map, nearly: X(xi) = X(0) + sum_i xi_i D_i + beta q(xi), q = xi1 xi2 xi3 (1 - xi1 - xi2 - xi3) (an affine
  // map plus a bubble): the fitted coefficients of every other monomial of degree >= 2 are zero, and those of q's
  // four monomials in the ratio 1 : -1 : -1 : -1, each within 1e-6 of the linear coefficients' size (fit's check;
  // the basis's own fit leaves them about 1e-13 off). A predictor for Newton's pull-back (pull_back3d.hpp), not
  // the map.
  bool bubble_form() const { return bubble_; }
  // With bubble_form(): D^-1 x (x relative to origin()) and v = D^-1 beta, so that the form is y where
  // xi + v q(xi) = D^-1 (y - X(0)).
  Point3 bubble_linear_inverse(Point3 x) const {
    const double(&m)[3][3] = bubble_inv_;
    return {m[0][0] * x.x + m[0][1] * x.y + m[0][2] * x.z, m[1][0] * x.x + m[1][1] * x.y + m[1][2] * x.z,
            m[2][0] * x.x + m[2][1] * x.y + m[2][2] * x.z};
  }
  Point3 bubble_direction() const { return bubble_v_; }
  Point3 bubble_beta() const { return bubble_beta_; }
  // D_i = dX/dxi_i of the affine part.
  Point3 bubble_linear(int i) const { return {c_[0][1 + i], c_[1][1 + i], c_[2][1 + i]}; }

  // "solid tetrahedron k", for error messages.
  std::string name() const { return "solid tetrahedron " + std::to_string(k); }
  // X at reference corner 0, the fitted polynomial's constant term (fitted_degree() >= 1).
  Point3 origin() const { return {c_[0][0], c_[1][0], c_[2][0]}; }
  // X(xi) - origin() (the constant term left out: to the relative precision of the tetrahedron's image
  // wherever it lies) and d[i] = dX/dxi_i, of the fitted polynomial (fitted_degree() >= 1).
  void displacement(Point3 xi, Point3& x, Point3 d[3]) const { polynomial(xi, x, d, 1); }
  // X(xi) - origin() alone (the same value as displacement's x, bit for bit).
  Point3 displacement_position(Point3 xi) const { return polynomial_value(xi, 1); }

 protected:
  const SolidMap3* map_ = nullptr;
  int degree_ = -1;
  double c_[3][monomial_count3(kMaxDegree)];  // monomial coefficients of X, Y, Z

 private:
  // value and reference-coordinate derivatives d[i] = dX/dxi_i of the fitted polynomial, its value summed
  // from monomial first on (0: X, 1: X - origin())
  void polynomial(Point3 xi, Point3& x, Point3 d[3], int first = 0) const;
  // its value alone, summed in the same order
  Point3 polynomial_value(Point3 xi, int first) const;
  double inv_[3][3];  // d xi / d s
  // The monomials whose coefficients are not all zero, ascending (a P1b map's: 8 of 35), which the sums read.
  int terms_[monomial_count3(kMaxDegree)] = {};
  int term_count_ = 0;
  // bubble_form()'s: whether, D^-1, D^-1 beta and beta
  void detect_bubble();
  bool bubble_ = false;
  double bubble_inv_[3][3] = {};
  Point3 bubble_v_, bubble_beta_;
};

}  // namespace dlmfsi
