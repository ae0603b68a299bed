#include "fe/affine_element_maps3d.hpp"

#include "buffer_room.hpp"

namespace dlmfsi {

AffineElementMaps3::AffineElementMaps3(const Mesh3& mesh)
    : mesh_(mesh), inverse_jacobian_(huge_buffer<double>(9 * static_cast<size_t>(mesh.size()))) {
  for (int k = 0; k < mesh.size(); ++k) {
    // x = p0 + E xi with E = [e1 e2 e3]: E^-1 has rows (e2 x e3, e3 x e1, e1 x e2) / det E
    Point3 p[4];
    mesh.corners(k, p);
    const Point3 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0];
    const double det = dot(e1, cross(e2, e3));
    const Point3 rows[3] = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
    double* j = inverse_jacobian_.get() + 9 * static_cast<size_t>(k);
    for (int r = 0; r < 3; ++r) {
      j[3 * r] = rows[r].x / det;
      j[3 * r + 1] = rows[r].y / det;
      j[3 * r + 2] = rows[r].z / det;
    }
  }
}

}  // namespace dlmfsi
