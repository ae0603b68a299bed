// The affine maps of a mesh's straight triangles, x = p0 + xi1 e1 + xi2 e2 (e1 = p1 - p0, e2 = p2 - p0, p0,
// p1, p2 the corners), inverted: per element d xi / d x = [e1 e2]^-1.
#pragma once
#include <cstddef>
#include <memory>

#include "buffer_room.hpp"
#include "mesh/mesh.hpp"

namespace dlmfsi {

class AffineElementMaps {
 public:
  explicit AffineElementMaps(const Mesh& mesh);

  // d xi / d x on element k, row by row: dxi1/dx, dxi1/dy, dxi2/dx, dxi2/dy.
  const double* inverse_jacobian(int k) const { return inverse_jacobian_.get() + 4 * static_cast<size_t>(k); }

  void prefetch(int k) const { __builtin_prefetch(inverse_jacobian(k)); }

  // The reference coordinates of point x in element k.
  Point to_reference(int k, Point x) const {
    const double* j = inverse_jacobian(k);
    const Point d = x - mesh_.vertex(k, 0);
    return {j[0] * d.x + j[1] * d.y, j[2] * d.x + j[3] * d.y};
  }
  // The same for x given relative to origin (x_local = x - origin), with element k's first corner translated
  // exactly by -origin (the caller's condition; FluidSearchOf checks it for the elements it visits): the
  // difference x - corner is then formed from the local coordinates. Origin 0 gives to_reference(k, x).
  Point to_reference(int k, Point x_local, Point origin) const {
    const double* j = inverse_jacobian(k);
    const Point d = x_local - (mesh_.vertex(k, 0) - origin);
    return {j[0] * d.x + j[1] * d.y, j[2] * d.x + j[3] * d.y};
  }

 private:
  const Mesh& mesh_;
  HugeBuffer<double> inverse_jacobian_;  // 4 entries per element, each written by the constructor
};

}  // namespace dlmfsi
