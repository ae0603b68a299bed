// The affine map x = p0 + E xi of each tetrahedron of a mesh from its reference coordinates, kept as
// E^-1 = d xi / d x (rows (e2 x e3, e3 x e1, e1 x e2) / det E, E = [e1 e2 e3] the edges from corner 0).
#pragma once
#include <cstddef>

#include "buffer_room.hpp"
#include "mesh/mesh3d.hpp"

namespace dlmfsi {

class AffineElementMaps3 {
 public:
  explicit AffineElementMaps3(const Mesh3& mesh);
  // The reference coordinates of x in element k.
  Point3 to_reference(int k, Point3 x) const {
    const double* j = inverse_jacobian_.get() + 9 * static_cast<size_t>(k);
    const Point3 d = x - mesh_.vertex(k, 0);
    return {j[0] * d.x + j[1] * d.y + j[2] * d.z, j[3] * d.x + j[4] * d.y + j[5] * d.z,
            j[6] * d.x + j[7] * d.y + j[8] * d.z};
  }
  // The same for x given relative to origin (x_local = x - origin), element k's first corner translated
  // exactly by -origin (the caller's condition; FluidSearchOf checks it for the elements it visits).
  Point3 to_reference(int k, Point3 x_local, Point3 origin) const {
    const double* j = inverse_jacobian_.get() + 9 * static_cast<size_t>(k);
    const Point3 d = x_local - (mesh_.vertex(k, 0) - origin);
    return {j[0] * d.x + j[1] * d.y + j[2] * d.z, j[3] * d.x + j[4] * d.y + j[5] * d.z,
            j[6] * d.x + j[7] * d.y + j[8] * d.z};
  }
  // d xi_i / d x_j of element k, row-major.
  const double* inverse_jacobian(int k) const { return inverse_jacobian_.get() + 9 * static_cast<size_t>(k); }
  // The point of element k at reference coordinates xi.
  Point3 from_reference(int k, Point3 xi) const {
    const Point3 p0 = mesh_.vertex(k, 0);
    return p0 + (xi.x * (mesh_.vertex(k, 1) - p0) + xi.y * (mesh_.vertex(k, 2) - p0) + xi.z * (mesh_.vertex(k, 3) - p0));
  }
  // The same relative to origin (corner 0 translated exactly by -origin).
  Point3 from_reference(int k, Point3 xi, Point3 origin) const {
    const Point3 p0 = mesh_.vertex(k, 0);
    return (p0 - origin) +
           (xi.x * (mesh_.vertex(k, 1) - p0) + xi.y * (mesh_.vertex(k, 2) - p0) + xi.z * (mesh_.vertex(k, 3) - p0));
  }
  // Edge i (= d x / d xi_(i+1)) of element k: corner i + 1 less corner 0.
  Point3 edge(int k, int i) const { return mesh_.vertex(k, i + 1) - mesh_.vertex(k, 0); }

 private:
  const Mesh3& mesh_;
  HugeBuffer<double> inverse_jacobian_;  // per element: d xi / d x, 9 entries, each written by the constructor
};

}  // namespace dlmfsi
