#include "map/pull_back3d.hpp"

#include <cmath>
#include <string>

#include "errors.hpp"

namespace dlmfsi {

namespace {

// A P1b map (bubble_form): X(xi) ~ o + D xi + beta q(xi). With v = D^-1 beta and xi0 = D^-1 (y - o), that is y
// where xi = xi0 - s v and s = q(xi0 - s v): a scalar equation g(s) = s - q(xi0 - s v) = 0, whose slope
// g' = 1 + grad q . v = det dX/dxi / det D is positive wherever the map does not fold. Newton on s, from the
// guess's s: each step evaluates q and its gradient at one point (Newton on X evaluates the degree-4 polynomial
// and its jacobian). Returns the guess itself where a slope is not positive or it does not settle: Newton on X
// then decides, as without this predictor.
Point3 bubble_predictor(const MappedTet& mt, Point3 y, Point3 guess) {
  const Point3 v = mt.bubble_direction(), xi0 = mt.bubble_linear_inverse(y - mt.origin());
  const double v1 = std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
  double s = dot(xi0 - guess, v) / dot(v, v);
  for (int it = 0; it < 20; ++it) {
    const Point3 p = xi0 - s * v;
    const double l0 = 1 - p.x - p.y - p.z;
    const Point3 gradient{p.y * p.z * (l0 - p.x), p.x * p.z * (l0 - p.y), p.x * p.y * (l0 - p.z)};
    const double slope = 1 + dot(gradient, v);
    if (!(slope > 0)) return guess;
    const double step = (s - p.x * p.y * p.z * l0) / slope;
    s -= step;
    if (std::fabs(step) * v1 < 1e-14) return xi0 - s * v;
  }
  return guess;
}

}  // namespace

Point3 pull_back(const MappedTet& mt, Point3 y, Point3 xi, MapValue3& value) {
  if (mt.affine) {
    value = mt.affine_value;
    value.x = y;
    return mt.affine_reference(y);
  }
  if (mt.bubble_form()) xi = bubble_predictor(mt, y, xi);
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
