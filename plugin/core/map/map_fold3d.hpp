// Does the map fold a solid tetrahedron? Where the map is not affine, det dX/dxi of its fitted polynomial is
// certified positive on the whole tetrahedron (fold3d.hpp); a map that is not a polynomial is sampled.
#pragma once
#include "map/fold3d.hpp"
#include "map/map3d.hpp"

namespace dlmfsi {

// The certification's limits: 10 levels of red refinement (det within about 4^-10 of zero, relative, is a
// near fold) and 4096 sub-tetrahedra tested per solid tetrahedron.
constexpr int kFoldDepth = 10;
constexpr int kFoldTetrahedra = 4096;

// det dX/dxi of mt's fitted polynomial at xi (mt.fitted_degree() >= 1) and a bound on its round-off.
DetSample jacobian_det(const MappedTet& mt, Point3 xi);

// Throws Error naming the tetrahedron when det dX/dxi is not positive somewhere on it ("folds": at a
// reference point given in the message) or comes within the limits above of zero ("nearly folds").
void check_fold(const MappedTet& mt);

}  // namespace dlmfsi
