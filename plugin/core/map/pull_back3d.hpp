// Newton's pull-back of a point of a tetrahedron's image to the tetrahedron's reference coordinates.
#pragma once
#include "map/mapped_element3d.hpp"

namespace dlmfsi {

// The reference point xi with X(xi) = y and the map there (value: X and dX/ds), by Newton's method from
// guess on mt's fitted polynomial (or on the map itself when it has none), stopping at |dxi| < 1e-12 or
// where the steps stall at the round-off floor; for an affine tetrahedron the affine inverse. Throws Error
// if it fails to converge or meets a jacobian determinant that is not positive (a folded map).
Point3 pull_back(const MappedTet& mt, Point3 y, Point3 guess, MapValue3& value);

}  // namespace dlmfsi
