// The affine map x = p0 + E xi of each tetrahedron of a mesh from its reference coordinates, kept as
// E^-1 = d xi / d x (rows (e2 x e3, e3 x e1, e1 x e2) / det E, E = [e1 e2 e3] the edges from corner 0).
#pragma once
#include <cstddef>
#include <vector>

#include "mesh3d.hpp"

namespace dlmfsi {

class TetFrames3 {
 public:
  explicit TetFrames3(const Mesh3& mesh);
  // The reference coordinates of x in element k.
  Point3 to_reference(int k, Point3 x) const {
    const double* j = &inverse_jacobian_[9 * static_cast<size_t>(k)];
    const Point3 d = x - mesh_.vertex(k, 0);
    return {j[0] * d.x + j[1] * d.y + j[2] * d.z, j[3] * d.x + j[4] * d.y + j[5] * d.z,
            j[6] * d.x + j[7] * d.y + j[8] * d.z};
  }
  // d xi_i / d x_j of element k, row-major.
  const double* inverse_jacobian(int k) const { return &inverse_jacobian_[9 * static_cast<size_t>(k)]; }

 private:
  const Mesh3& mesh_;
  std::vector<double> inverse_jacobian_;  // per element: d xi / d x, 9 entries
};

}  // namespace dlmfsi
