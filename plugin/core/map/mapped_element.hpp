// One solid triangle under the map X: the images of its corners, how its image may be handled (affine,
// straight edges, curved) and the pull-back of points of the image.
#pragma once
#include "map/solid_map.hpp"
#include "map/map_shape.hpp"
#include "mesh/mesh.hpp"
#include "map/pull_back.hpp"
#include "map/element_map.hpp"

namespace dlmfsi {

// X on the triangle (TriangleMap) and the triangle's image. A is the affine interpolant of the corner
// images: A(xi) = image[0] + xi1 (image[1] - image[0]) + xi2 (image[2] - image[0]).
class MappedTriangle : public TriangleMap {
 public:
  Point image[3];         // X at the corners
  bool affine = false;    // X agrees with A (to round-off)
  bool straight = false;  // the image's edges are straight segments (MapShape)
  double nonlinearity = 0;  // how far X is from A (MapShape): 0 for an affine map, folds from 1
  MapValue affine_value;  // for affine triangles: X at the first corner and the constant jacobian
  double affine_det = 0;  // det of that jacobian (> 0)

  // Fits X on solid triangle k, checks the corner images (finite, counter-clockwise, not degenerate: exact
  // predicates), classifies the map and, where it is not affine, certifies that its jacobian determinant
  // is positive on the whole triangle (check_fold); throws Error naming triangle k on bad input (NaN/Inf,
  // flat, inverted, folded).
  void prepare(const Mesh& solid_mesh, const SolidMap& map, int k);

  // The reference point xi with X(xi) = y and the map there: A^-1(y) for affine triangles, otherwise
  // newton_pull_back from A^-1(y).
  Point pull_back(Point y, MapValue& value) const {
    const Point xi = affine_reference(y);
    if (affine) {
      value = affine_value;
      value.x = y;
      return xi;
    }
    return newton_pull_back(*this, xi_round_off_, y, xi, value);
  }
  // The same from a starting point near the answer (e.g. interpolated from pulled-back points nearby).
  Point pull_back(Point y, Point guess, MapValue& value) const {
    if (affine) return pull_back(y, value);
    return newton_pull_back(*this, xi_round_off_, y, guess, value);
  }
  // The same at n points of a triangle that is not affine (newton_pull_back_points): xi the starting points
  // in, the answers out; jacobian: dX/ds there.
  void pull_back_points(int n, const Point* y, Point* xi, std::array<double, 4>* jacobian,
                        std::vector<double>& scratch) const {
    newton_pull_back_points(*this, xi_round_off_, n, y, xi, jacobian, scratch);
  }

  // The round-off of an area inside the image computed from `pieces` convex pieces whose corners are
  // rounded fluid coordinates: each corner is known to about eps |y|, so a piece's area to about
  // eps |y| times its perimeter. Below this, the area outside the fluid mesh is not resolved.
  double area_round_off(long pieces) const;

  // A^-1(y) (for affine triangles, the pull-back itself).
  Point affine_reference(Point y) const {
    const Point d = y - image[0];
    return {image_inv_[0][0] * d.x + image_inv_[0][1] * d.y, image_inv_[1][0] * d.x + image_inv_[1][1] * d.y};
  }
  // The same for y given relative to origin (y_local = y - origin), image[0] translated exactly by -origin
  // (the caller's condition). Origin 0 gives affine_reference(y).
  Point affine_reference(Point y_local, Point origin) const {
    const Point d = y_local - (image[0] - origin);
    return {image_inv_[0][0] * d.x + image_inv_[0][1] * d.y, image_inv_[1][0] * d.x + image_inv_[1][1] * d.y};
  }

 private:
  // The largest |coordinate| of the corner images.
  double magnitude() const;
  // The largest |coordinate| of the image's edges f1, f2 and f2 - f1.
  static double extent(Point f1, Point f2);
  static constexpr double kEps = 0x1p-52;
  // Newton's floor in reference coordinates: the residual y - X(xi) is known to about eps times the image's
  // size for a fitted map (formed relative to image[0]), eps |y| otherwise; this much in xi.
  double xi_round_off_ = 0;
  double image_inv_[2][2];  // A^-1 = d xi / d y
};

}  // namespace dlmfsi
