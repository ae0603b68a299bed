#include "pull_back.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.hpp"

namespace dlmfsi {

Point newton_pull_back(const TriangleMap& map, double xi_round_off, Point y, Point xi, MapValue& value) {
  // dX/dxi = [d1 d2] (d1, d2: the derivatives in xi1, xi2); its determinant has the sign of det dX/ds
  // (the solid triangle is counter-clockwise).
  const bool fitted = map.fitted();
  auto evaluate = [&](Point at_xi, Point& x, Point& d1, Point& d2) {
    if (fitted) {
      map.polynomial(at_xi, x, d1, d2);
      return;
    }
    value = map.evaluate(at_xi);
    x = value.x;
    map.reference_jacobian(value, d1, d2);
  };
  auto finish = [&](Point x, Point d1, Point d2) {
    if (!fitted) return;  // value already holds X and dX/ds there
    value.x = x;
    map.set_jacobian(d1, d2, value);
  };
  double previous = 1e300;
  Point last = xi, last_step{0, 0};  // the last iterate with a positive determinant, and the step from it
  for (int it = 0; it < 80; ++it) {
    Point x, d1, d2;
    evaluate(xi, x, d1, d2);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(det > 0)) {
      if (it == 0) throw Error("the map folds " + map.name() + " (jacobian determinant " + std::to_string(det) + ")");
      last_step = 0.5 * last_step;
      xi = last + last_step;
      continue;
    }
    const Point r = y - x;
    const Point step{(d2.y * r.x - d2.x * r.y) / det, (d1.x * r.y - d1.y * r.x) / det};
    last = xi;
    last_step = step;
    xi = xi + step;
    const double size = std::fabs(step.x) + std::fabs(step.y);
    // Converged: the jacobian just computed is off by O(size) times the map's small nonlinearity.
    if (size < std::max(1e-12, xi_round_off)) {
      finish(x, d1, d2);
      return xi;
    }
    // Stalled at the round-off floor (quadratic convergence would have halved the step).
    if (size < std::max(1e-9, 64 * xi_round_off) && size > 0.5 * previous) {
      evaluate(xi, x, d1, d2);
      finish(x, d1, d2);
      return xi;
    }
    previous = size;
  }
  throw Error("Newton's method did not converge pulling a point back into " + map.name());
}

}  // namespace dlmfsi
