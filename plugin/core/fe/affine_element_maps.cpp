#include "fe/affine_element_maps.hpp"

#include "buffer_room.hpp"

namespace dlmfsi {

AffineElementMaps::AffineElementMaps(const Mesh& mesh)
    : mesh_(mesh), inverse_jacobian_(huge_buffer<double>(4 * static_cast<size_t>(mesh.size()))) {
  for (int k = 0; k < mesh.size(); ++k) {
    // [e1 e2]^-1 = [[e2.y, -e2.x], [-e1.y, e1.x]] / det [e1 e2]
    Point p[3];
    mesh.corners(k, p);
    const Point e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double det = cross(e1, e2);
    double* j = inverse_jacobian_.get() + 4 * static_cast<size_t>(k);
    j[0] = e2.y / det;
    j[1] = -e2.x / det;
    j[2] = -e1.y / det;
    j[3] = e1.x / det;
  }
}

}  // namespace dlmfsi
