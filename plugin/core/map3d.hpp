// The map X that places a 3D solid: values, derivatives, shape of each mapped tetrahedron, pull-back
// (the counterpart of map.hpp).
#pragma once
#include <vector>

#include "basis.hpp"
#include "fold3d.hpp"
#include "lattice3d.hpp"
#include "mesh3d.hpp"
#include "polynomial_basis3d.hpp"

namespace dlmfsi {

struct MapValue3 {
  Point3 x;           // X(s)
  double jac[3][3];   // jac[a][b] = dX_a / ds_b, derivatives in the solid's reference coordinates s
};

inline double det3(const double j[3][3]) {
  return j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
         j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
}

class SolidMap3 {
 public:
  virtual ~SolidMap3() = default;
  // X at reference point xi of solid tetrahedron k. Must be safe to call from several threads at once.
  virtual MapValue3 evaluate(int k, Point3 xi) const = 0;
  // The polynomial degree of X on each tetrahedron (1 to 6), or -1 when unknown or not polynomial.
  virtual int degree() const { return -1; }
  // The monomial coefficients (lattice3d.hpp order, degree()) of X, Y and Z on tetrahedron k in the
  // reference coordinates, or false to let the caller fit them from evaluate().
  virtual bool coefficients(int, double*, double*, double*) const { return false; }
  // X at the four corners of tetrahedron k, exactly as the map's own values there (so that tetrahedra
  // sharing a vertex agree on its image bit for bit), or false to let the caller evaluate them.
  virtual bool corners(int, Point3*) const { return false; }
};

// X = (sum_i x_i phi_i^cx, sum_i y_i phi_i^cy, sum_i z_i phi_i^cz): components of finite element functions
// on the solid mesh (three scalar functions, or components of one vector function). For polynomial
// spaces the monomial coefficients of X on every tetrahedron are computed once, here, from the spaces' fits
// (given in fit[] when the caller keeps them across calls, otherwise fitted here).
class FieldMap3 : public SolidMap3 {
 public:
  FieldMap3(const Mesh3& solid, const Basis3* const space[3], const double* const coef[3], const int comp[3],
            const PolynomialBasis3* const fit[3] = nullptr);
  // The degree the map is fitted to: the highest polynomial degree of the three components, or -1 when one
  // is not polynomial or the degree lies outside 1..6. Throws Error for a component out of range.
  static int fit_degree(const Basis3* const space[3], const int comp[3]);
  MapValue3 evaluate(int k, Point3 xi) const override;
  int degree() const override { return degree_; }
  bool coefficients(int k, double* cx, double* cy, double* cz) const override;
  bool corners(int k, Point3* out) const override;

 private:
  struct Part {
    const Basis3* space;
    const double* coef;
    int comp, first, last;
  };
  Part part_[3];
  int degree_ = -1;
  std::vector<double> monomial_coef_;  // per tetrahedron: x, y then z coefficients
  // Per part and corner of the reference tetrahedron: the local dof whose basis function is 1 there while
  // the part's others are 0 (a Lagrange dof at the vertex), or -1; valid on tetrahedra of the shared fit.
  int corner_dof_[3][4];
  std::vector<char> corner_exact_;  // per tetrahedron: every part uses the shared fit and has corner dofs
};

// One solid tetrahedron k under the map: the images of its corners and how its image may be handled.
// When the map's degree is known, X is fitted on the tetrahedron's lattice (exact for a polynomial map)
// and evaluated as a polynomial in the reference coordinates.
class MappedTet {
 public:
  static constexpr int kMaxDegree = 6;
  // The fold certification's limits (fold3d.hpp): 10 levels of red refinement (det within about 4^-10 of
  // zero, relative, is a near fold) and 4096 sub-tetrahedra tested per solid tetrahedron.
  static constexpr int kFoldDepth = 10;
  static constexpr int kFoldTetrahedra = 4096;
  int k = -1;
  Point3 solid[4];   // corners in the reference configuration
  Point3 image[4];   // X at the corners
  bool affine = false;  // X agrees with the affine interpolant of the corner images (to round-off)
  bool planar = false;  // the image's faces are planar (e.g. P1b: the bubble vanishes on faces)
  // max |G^-1 dX/dxi - I| (G = dX/dxi of the affine interpolant of the corners, max row sum) at sample points:
  // how far the map's jacobian strays from the affine one, which sets the quadrature degree needed
  double nonlinearity = 0;
  MapValue3 affine_value;   // for affine tetrahedra: X at the first corner and the constant jacobian
  double affine_det = 0;    // det of that jacobian (> 0)

  // Checks the corners (finite, image positively oriented, not flat: exact predicates) and classifies the
  // map; throws Error naming tetrahedron k on bad input (NaN/Inf, flat, inverted).
  void prepare(const Mesh3& solid_mesh, const SolidMap3& map, int k);

  // X and its jacobian (with respect to s) at reference point xi.
  MapValue3 at(Point3 xi) const;
  // X and its reference-coordinate derivatives d[i] = dX/dxi_i at xi (of the fitted polynomial, or of the
  // map itself when its degree is unknown).
  void reference_derivatives(Point3 xi, Point3& x, Point3 d[3]) const;

  // The reference point of y under the affine interpolant of the corner images (for affine tetrahedra,
  // the pull-back itself).
  Point3 affine_reference(Point3 y) const {
    const Point3 d = y - image[0];
    const double(&m)[3][3] = image_inv_;
    return {m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z, m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
            m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z};
  }

  // The reference point xi with X(xi) = y and the map there, by Newton's method from guess, stopping at
  // |dxi| < 1e-12 or where the steps stall at the round-off floor. Throws Error if it fails to converge or
  // the jacobian determinant is not positive (a folded map).
  Point3 pull_back(Point3 y, Point3 guess, MapValue3& value) const;

 private:
  void classify();
  // Throws Error when det dX/dxi is not certified positive on the whole tetrahedron (fold3d.hpp).
  void check_fold() const;
  // det dX/dxi of the fitted polynomial at xi and a bound on its round-off.
  DetSample jacobian_det(Point3 xi) const;
  // value and reference-coordinate derivatives d[i] = dX/dxi_i of the fitted polynomial
  void polynomial(Point3 xi, Point3& x, Point3 d[3]) const;
  void set_jacobian(const Point3 d[3], MapValue3& v) const;  // v.jac = dX/dxi (ds/dxi)^-1
  const SolidMap3* map_ = nullptr;
  int degree_ = -1;
  double c_[3][monomial_count3(kMaxDegree)];  // monomial coefficients of X, Y, Z
  double inv_[3][3];        // d xi / d s
  double image_inv_[3][3];  // d xi / d y of the affine interpolant of the corner images
};

}  // namespace dlmfsi
