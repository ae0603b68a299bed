// The map X that places the solid: values, derivatives, shape of each mapped triangle, pull-back.
#pragma once
#include <vector>

#include "basis.hpp"
#include "mesh.hpp"
#include "polynomial_basis.hpp"

namespace dlmfsi {

struct MapValue {
  Point x;             // X(s)
  double jac[2][2];    // jac[a][b] = dX_a / ds_b, derivatives in the solid's reference coordinates s
};

class SolidMap {
 public:
  virtual ~SolidMap() = default;
  // X at reference point xi of solid triangle k. Must be safe to call from several threads at once.
  virtual MapValue evaluate(int k, Point xi) const = 0;
  // The polynomial degree of X on each triangle (1 to 6), or -1 when unknown or not polynomial.
  virtual int degree() const { return -1; }
  // The monomial coefficients (lattice.hpp order, degree()) of X and Y on triangle k in the reference
  // coordinates, or false to let the caller fit them from evaluate().
  virtual bool coefficients(int, double*, double*) const { return false; }
};

// X = (sum_i x_i phi_i^cx, sum_i y_i phi_i^cy): components of finite element functions on the solid mesh
// (two scalar functions, or two components of one vector function). For polynomial spaces the monomial
// coefficients of X on every solid triangle are computed once, here, from the spaces' fits on the map's
// components: fit_x and fit_y when the caller keeps them across calls (PolynomialBasis(space, solid,
// fit_degree(...), {comp})), otherwise fitted here.
class FieldMap : public SolidMap {
 public:
  FieldMap(const Mesh& solid, const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y,
           const double* coef_y, int comp_y, const PolynomialBasis* fit_x = nullptr,
           const PolynomialBasis* fit_y = nullptr);
  // The degree the map is fitted to: the higher polynomial degree of the two components, or -1 when one is
  // not polynomial or the degree lies outside 1..6 (the map is then evaluated through the spaces). Throws
  // Error for a component out of range.
  static int fit_degree(const Basis& space_x, int comp_x, const Basis& space_y, int comp_y);
  MapValue evaluate(int k, Point xi) const override;
  int degree() const override { return degree_; }
  bool coefficients(int k, double* cx, double* cy) const override;

 private:
  struct Part {
    const Basis* space;
    const double* coef;
    int comp, first, last;
  };
  Part part_[2];
  int degree_ = -1;
  std::vector<double> monomial_coef_;  // per triangle: x then y coefficients
};

// One solid triangle k under the map: the images of its corners and how its image may be handled.
// When the map's degree d is known, X is fitted once on the triangle's degree-d lattice (exact for a
// polynomial map) and then evaluated as a polynomial in the reference coordinates, which makes
// Newton's pull-back and the shape tests cheap.
class MappedTriangle {
 public:
  static constexpr int kMaxDegree = 6;
  int k = -1;
  Point solid[3];    // corners in the reference configuration
  Point image[3];    // X at the corners
  bool affine = false;    // X agrees with the affine interpolant of the corner images (to round-off)
  bool straight = false;  // the image's edges are straight segments (e.g. P1b: the bubble vanishes on edges)
  // How far X is from affine on the triangle: the largest || A^-1 dX/dxi - I || (rows' absolute sums) over
  // sample points, A the jacobian of the affine interpolant of the corner images. 0 for an affine map; the
  // map folds where it reaches 1 in some direction (2 for a P1b bubble moved 4/9 of the way to a corner).
  double nonlinearity = 0;
  MapValue affine_value;  // for affine triangles: X at the first corner and the constant jacobian
  double affine_det = 0;  // det of that jacobian (> 0)

  // Checks the corners (finite, image counter-clockwise, not degenerate: exact predicates), classifies the
  // map and, where it is not affine, certifies that its jacobian determinant is positive on the whole
  // triangle (fold.hpp; sampled when the map is not polynomial); throws Error naming triangle k on bad
  // input (NaN/Inf, flat, inverted, folded).
  void prepare(const Mesh& solid_mesh, const SolidMap& map, int k);

  // X and its derivatives in the reference coordinates, d1 = dX/dxi1 and d2 = dX/dxi2, at xi.
  void reference_derivatives(Point xi, Point& x, Point& d1, Point& d2) const;

  // The nonlinearity (as above) of X on the sub-triangle of reference corners ref whose images are img,
  // sampled at its corners, edge midpoints and centroid.
  double nonlinearity_on(const Point ref[3], const Point img[3]) const;

  // X and its jacobian (with respect to s) at reference point xi.
  MapValue at(Point xi) const;

  // The reference point xi with X(xi) = y and the map there; for non-affine triangles Newton's method
  // from the affine guess, stopping at |dxi| < 1e-12 or where the steps stall at the round-off floor.
  // Where the determinant is not positive at an iterate, the step is halved back towards the previous
  // iterate (a point beyond the triangle, where a map that is valid on it may fold).
  // Throws Error if it fails to converge or the jacobian determinant is not positive at the start.
  Point pull_back(Point y, MapValue& value) const;
  // The same from a starting point near the answer (e.g. interpolated from pulled-back points nearby).
  Point pull_back(Point y, Point guess, MapValue& value) const;

  // The round-off of an area inside the image computed from `pieces` convex pieces whose corners are
  // rounded fluid coordinates: each corner is known to about eps |y|, so a piece's area to about
  // eps |y| times its perimeter. Below this, the area outside the fluid mesh is not resolved.
  double area_round_off(long pieces) const;

  // The reference point of y under the affine interpolant of the corner images (for affine triangles, the
  // pull-back itself).
  Point affine_reference(Point y) const {
    const Point d = y - image[0];
    return {image_inv_[0][0] * d.x + image_inv_[0][1] * d.y, image_inv_[1][0] * d.x + image_inv_[1][1] * d.y};
  }

 private:
  // Sets affine, straight and nonlinearity by sampling X at edge and interior points.
  void classify();
  // Throws Error when the jacobian determinant is not positive somewhere on the triangle.
  void check_fold() const;
  // The largest |coordinate| of the corner images.
  double magnitude() const;
  // || A^-1 dX/dxi(xi) - I || (see nonlinearity).
  double jacobian_variation(Point xi) const;
  // value and reference-coordinate derivatives of the fitted polynomial
  void polynomial(Point xi, Point& x, Point& dx1, Point& dx2) const;
  // v.jac = dX/ds from the reference derivatives d1 = dX/dxi1, d2 = dX/dxi2
  void set_jacobian(Point d1, Point d2, MapValue& v) const;
  static constexpr double kEps = 0x1p-52;
  const SolidMap* map_ = nullptr;
  int degree_ = -1;
  // Newton's floor in reference coordinates: a point y is known to about eps |y|, which is this much in xi
  // (small triangles far from the origin: 1e-9 for a triangle of 1e-7 at distance 1).
  double xi_round_off_ = 0;
  double cx_[(kMaxDegree + 1) * (kMaxDegree + 2) / 2], cy_[(kMaxDegree + 1) * (kMaxDegree + 2) / 2];  // monomial coefficients
  double inv_[2][2];        // (d s / d xi)^-1
  double image_inv_[2][2];  // (d xi / d y) of the affine interpolant of the corner images
};

inline double det2(const double j[2][2]) { return j[0][0] * j[1][1] - j[0][1] * j[1][0]; }

}  // namespace dlmfsi
