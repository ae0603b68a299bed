#include "map/pull_back3d.hpp"

#include <cmath>
#include <string>

#include "errors.hpp"

namespace dlmfsi {

Point3 pull_back(const MappedTet& mt, Point3 y, Point3 xi, MapValue3& value) {
  if (mt.affine) {
    value = mt.affine_value;
    value.x = y;
    return mt.affine_reference(y);
  }
  // Newton on X(xi) = y with dX/dxi = [d1 d2 d3]; its determinant has the sign of det dX/ds. A fitted map's
  // residual is (y - o) - (X(xi) - o), o = X(0): each difference to the relative precision of the image's
  // size, so that a small tetrahedron far from 0 converges as near 0. x below is X - o.
  const bool fitted = mt.fitted_degree() >= 1;
  const Point3 o = fitted ? mt.origin() : Point3{0, 0, 0};
  const Point3 y_o = y - o;
  const Point3 e[3] = {mt.solid[1] - mt.solid[0], mt.solid[2] - mt.solid[0], mt.solid[3] - mt.solid[0]};
  auto evaluate = [&](Point3 at_xi, Point3& x, Point3 d[3]) {
    if (fitted) {
      mt.displacement(at_xi, x, d);
      return;
    }
    value = mt.at(at_xi);  // the map's own value and dX/ds
    x = value.x;
    for (int i = 0; i < 3; ++i)  // dX/dxi_i = dX/ds e_i
      d[i] = {value.jac[0][0] * e[i].x + value.jac[0][1] * e[i].y + value.jac[0][2] * e[i].z,
              value.jac[1][0] * e[i].x + value.jac[1][1] * e[i].y + value.jac[1][2] * e[i].z,
              value.jac[2][0] * e[i].x + value.jac[2][1] * e[i].y + value.jac[2][2] * e[i].z};
  };
  auto finish = [&](Point3 x, const Point3 d[3]) {
    if (!fitted) return;  // value already holds X and dX/ds there
    value.x = o + x;
    mt.set_jacobian(d, value);
  };
  double previous = 1e300;
  for (int it = 0; it < 40; ++it) {
    Point3 x, d[3];
    evaluate(xi, x, d);
    const double det = dot(d[0], cross(d[1], d[2]));
    if (!(det > 0)) throw Error("the map folds " + mt.name() + " (jacobian determinant " + std::to_string(det) + ")");
    const Point3 r = y_o - x;
    // Cramer: step = [d1 d2 d3]^-1 r
    const Point3 step{dot(r, cross(d[1], d[2])) / det, dot(d[0], cross(r, d[2])) / det,
                      dot(d[0], cross(d[1], r)) / det};
    xi = xi + step;
    const double size = std::fabs(step.x) + std::fabs(step.y) + std::fabs(step.z);
    if (size < 1e-12) {
      finish(x, d);
      return xi;
    }
    // Stalled at the round-off floor (quadratic convergence would have halved the step).
    if (size < 1e-9 && size > 0.5 * previous) {
      evaluate(xi, x, d);
      finish(x, d);
      return xi;
    }
    previous = size;
  }
  throw Error("Newton's method did not converge pulling a point back into " + mt.name());
}

}  // namespace dlmfsi
