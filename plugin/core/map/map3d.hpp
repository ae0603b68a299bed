// One solid tetrahedron under the map X (solid_map3d.hpp): its image's corners and shape, X as a polynomial
// in its reference coordinates (the counterpart of map.hpp's MappedTriangle; the pull-back: pull_back3d.hpp).
#pragma once
#include "fe/lattice3d.hpp"
#include "mesh/mesh3d.hpp"
#include "map/solid_map3d.hpp"

namespace dlmfsi {

// One solid tetrahedron k under the map: the images of its corners and how its image may be handled.
// When the map's degree is known, X is fitted on the tetrahedron's lattice (exact for a polynomial map)
// and evaluated as a polynomial in the reference coordinates.
class MappedTet {
 public:
  static constexpr int kMaxDegree = kMaxMapDegree3;
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
  // v.jac = dX/ds from the reference-coordinate derivatives d[i] = dX/dxi_i: dX/dxi (ds/dxi)^-1.
  void set_jacobian(const Point3 d[3], MapValue3& v) const;
  // The degree of the polynomial fitted to X (1 to kMaxDegree), or -1 when X is evaluated itself.
  int fitted_degree() const { return degree_; }
  // The monomial coefficients (lattice3d.hpp order) of component a of the fitted polynomial.
  const double* coefficients(int a) const { return c_[a]; }
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


 private:
  void classify();
  // value and reference-coordinate derivatives d[i] = dX/dxi_i of the fitted polynomial
  void polynomial(Point3 xi, Point3& x, Point3 d[3]) const;
  const SolidMap3* map_ = nullptr;
  int degree_ = -1;
  double c_[3][monomial_count3(kMaxDegree)];  // monomial coefficients of X, Y, Z
  double inv_[3][3];        // d xi / d s
  double image_inv_[3][3];  // d xi / d y of the affine interpolant of the corner images
};

}  // namespace dlmfsi
