// One solid tetrahedron under the map X (solid_map3d.hpp): X on it (element_map3d.hpp), its image's corners
// and shape (the counterpart of mapped_element.hpp's MappedTriangle; the pull-back: pull_back3d.hpp).
#pragma once
#include "map/element_map3d.hpp"

namespace dlmfsi {

// One solid tetrahedron k under the map: the images of its corners and how its image may be handled.
// When the map's degree is known, X is fitted on the tetrahedron's lattice (exact for a polynomial map)
// and evaluated as a polynomial in the reference coordinates.
class MappedTet : public TetrahedronMap {
 public:
  Point3 image[4];   // X at the corners
  bool affine = false;  // X agrees with the affine interpolant of the corner images (to round-off)
  bool planar = false;  // the image's faces are planar (e.g. P1b: the bubble vanishes on faces)
  // max |G^-1 dX/dxi - I| (G = dX/dxi of the affine interpolant of the corners, max row sum) at sample points:
  // how far the map's jacobian strays from the affine one, which sets the quadrature degree needed
  double nonlinearity = 0;
  MapValue3 affine_value;   // for affine tetrahedra: X at the first corner and the constant jacobian
  double affine_det = 0;    // det of that jacobian (> 0)

  // Fits X (TetrahedronMap::fit), checks the corner images (finite, positively oriented, not flat: exact
  // predicates), classifies the map and certifies that it does not fold (fold3d.hpp); throws Error naming
  // tetrahedron k on bad input (NaN/Inf, flat, inverted, folded).
  void prepare(const Mesh3& solid_mesh, const SolidMap3& map, int k);

  // The reference point of y under the affine interpolant of the corner images (for affine tetrahedra,
  // the pull-back itself).
  Point3 affine_reference(Point3 y) const {
    const Point3 d = y - image[0];
    const double(&m)[3][3] = image_inv_;
    return {m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z, m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
            m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z};
  }
  // The same for y given relative to origin (y_local = y - origin), image[0] translated exactly by -origin
  // (the caller's condition). Origin 0 gives affine_reference(y).
  Point3 affine_reference(Point3 y_local, Point3 origin) const {
    const Point3 d = y_local - (image[0] - origin);
    const double(&m)[3][3] = image_inv_;
    return {m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z, m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
            m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z};
  }

 private:
  void classify();
  double image_inv_[3][3];  // d xi / d y of the affine interpolant of the corner images
};

}  // namespace dlmfsi
