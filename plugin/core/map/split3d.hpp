// The straight image of a solid tetrahedron (or of a sub-tetrahedron of a curved one) split into parts on
// each of which the map is nearly affine (the 3D counterpart of split.hpp).
//
// On a piece of an image the coupling integrates f(X^-1(y)) / det dX(X^-1(y)) in fluid coordinates y; a rule
// of degree p + q is accurate when the map's nonlinearity on the piece is small, and converges slowly near a
// fold, where det dX vanishes. The split is done in fluid coordinates: a part (the straight tetrahedron y
// and the reference points xi with X(xi_i) = y_i) is cut by red refinement of y into 8 (the midpoints of its
// edges, their reference points by Newton's pull-back), so the parts tile the straight tetrahedron that was
// split (up to the rounding of the midpoints, shared by the parts that meet there) and the integration
// domain does not change; only the rules' accuracy does.
#pragma once
#include <vector>

#include "map/mapped_element3d.hpp"

namespace dlmfsi {

struct MapPart3 {
  Point3 y[4];          // the part, positively oriented, in fluid coordinates
  Point3 xi[4];         // reference points whose images are its corners
  double nonlinearity;  // of the map on the part (nonlinearity_on)
};

// max || A^-1 dX/dxi - I || (max row sum) at 27 points (split3d.cpp) of the
// reference tetrahedron xi, A = [y_i - y_0] [xi_i - xi_0]^-1 the affine map from xi to y: how far the map
// strays from the affine one on the part (MappedTet::nonlinearity for the whole tetrahedron). 1e300 when y
// is flat or negatively oriented in floating point.
double nonlinearity_on(const MappedTet& mt, const Point3 xi[4], const Point3 y[4]);

// Splits (xi, y) until every part's nonlinearity is at most target, into parts; returns false when a part
// above target is max_depth levels down or the parts would exceed max_parts (the map nearly folds).
// Throws Error when Newton's pull-back of a midpoint fails or meets a non-positive jacobian determinant.
bool split_part3(const MappedTet& mt, const Point3 xi[4], const Point3 y[4], double target, int max_depth,
                 int max_parts, std::vector<MapPart3>& parts);

}  // namespace dlmfsi
