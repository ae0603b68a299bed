#include "integration/integrator3d.hpp"


namespace dlmfsi {

Point3 ClippedImage3::guess(Point3 y) const {
  if (!sub_xi) return tetrahedron.affine_reference(y, origin);
  // y = y0 + [e1 e2 e3] l: l by Cramer's rule, then xi = xi0 + sum_i l_i (xi_i - xi0); y relative to origin
  // (sub_y[0] - origin: exact where the origin is sub_y[0]'s coordinate, ExactMethod3::local_origin)
  const Point3 e1 = sub_y[1] - sub_y[0], e2 = sub_y[2] - sub_y[0], e3 = sub_y[3] - sub_y[0],
               r = y - (sub_y[0] - origin);
  const double det = dot(e1, cross(e2, e3));
  const double l1 = dot(r, cross(e2, e3)) / det, l2 = dot(e1, cross(r, e3)) / det, l3 = dot(e1, cross(e2, r)) / det;
  return sub_xi[0] + (l1 * (sub_xi[1] - sub_xi[0]) + l2 * (sub_xi[2] - sub_xi[0]) + l3 * (sub_xi[3] - sub_xi[0]));
}

}  // namespace dlmfsi
