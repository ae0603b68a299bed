#include "map/pull_back.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.hpp"

namespace dlmfsi {

Point newton_pull_back(const TriangleMap& map, double xi_round_off, Point y, Point xi, MapValue& value) {
  // dX/dxi = [d1 d2] (d1, d2: the derivatives in xi1, xi2); its determinant has the sign of det dX/ds
  // (the solid triangle is counter-clockwise). A fitted map's residual is (y - o) - (X(xi) - o), o = X(0, 0),
  // each difference to the relative precision of the image's size: a small triangle far from 0 converges as
  // near 0. x below is X - o.
  const bool fitted = map.fitted();
  const Point o = fitted ? map.origin() : Point{0, 0};
  const Point y_o = y - o;
  auto evaluate = [&](Point at_xi, Point& x, Point& d1, Point& d2) {
    if (fitted) {
      map.displacement(at_xi, x, d1, d2);
      return;
    }
    value = map.evaluate(at_xi);
    x = value.x;
    map.reference_jacobian(value, d1, d2);
  };
  auto finish = [&](Point x, Point d1, Point d2) {
    if (!fitted) return;  // value already holds X and dX/ds there
    value.x = o + x;
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
    const Point r = y_o - x;
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

namespace {

// newton_pull_back's step at n points (the same operations): t = (dX/dxi)^-1 (y - x), dX/dxi = [a b].
void newton_steps(int n, const double* __restrict y0, const double* __restrict y1, const double* __restrict x0,
                  const double* __restrict x1, const double* __restrict a0, const double* __restrict a1,
                  const double* __restrict b0, const double* __restrict b1, double* __restrict t1,
                  double* __restrict t2) {
  for (int q = 0; q < n; ++q) {
    const double det = a0[q] * b1[q] - b0[q] * a1[q];
    const double rx = y0[q] - x0[q], ry = y1[q] - x1[q];
    t1[q] = (b1[q] * rx - b0[q] * ry) / det;
    t2[q] = (a0[q] * ry - a1[q] * rx) / det;
  }
}

}  // namespace

void newton_pull_back_points(const TriangleMap& map, double xi_round_off, int n, const Point* y, Point* xi,
                             std::array<double, 4>* jacobian, std::vector<double>& scratch) {
  auto scalar = [&](int q) {
    MapValue value;
    xi[q] = newton_pull_back(map, xi_round_off, y[q], xi[q], value);
    jacobian[q] = {value.jac[0][0], value.jac[0][1], value.jac[1][0], value.jac[1][1]};
  };
  if (!map.fitted()) {
    for (int q = 0; q < n; ++q) scalar(q);
    return;
  }
  const Point o = map.origin();
  const size_t m = static_cast<size_t>(n);
  if (scratch.size() < 13 * m) scratch.resize(13 * m);
  // the iterates (s1, s2), X - o there (x0, x1) with o = X(0, 0), its reference derivatives d1 = (a0, a1), d2 = (b0, b1), the
  // steps (t1, t2), the points minus o (y0, y1) and each point's state: 0 iterating, 1 converged (xi and jacobian
  // set), 2 to be redone
  double *s1 = scratch.data(), *s2 = s1 + m, *x0 = s2 + m, *x1 = x0 + m, *a0 = x1 + m, *a1 = a0 + m;
  double *b0 = a1 + m, *b1 = b0 + m, *t1 = b1 + m, *t2 = t1 + m, *y0 = t2 + m, *y1 = y0 + m, *state = y1 + m;
  for (int q = 0; q < n; ++q) {
    s1[q] = xi[q].x;
    s2[q] = xi[q].y;
    y0[q] = y[q].x - o.x;
    y1[q] = y[q].y - o.y;
    state[q] = 0;
  }
  const double converged = std::max(1e-12, xi_round_off);
  for (int it = 0; it < 2; ++it) {
    map.displacement_points(n, s1, s2, x0, x1, a0, a1, b0, b1);
    newton_steps(n, y0, y1, x0, x1, a0, a1, b0, b1, t1, t2);
    for (int q = 0; q < n; ++q) {
      if (state[q] != 0) continue;
      const double det = a0[q] * b1[q] - b0[q] * a1[q];
      const double step = std::fabs(t1[q]) + std::fabs(t2[q]);
      if (!(det > 0)) {
        state[q] = 2;
      } else if (step < converged) {
        state[q] = 1;
        xi[q] = Point{s1[q], s2[q]} + Point{t1[q], t2[q]};
        MapValue value;
        map.set_jacobian({a0[q], a1[q]}, {b0[q], b1[q]}, value);
        jacobian[q] = {value.jac[0][0], value.jac[0][1], value.jac[1][0], value.jac[1][1]};
      } else if (it == 1) {
        state[q] = 2;
      } else {
        s1[q] += t1[q];
        s2[q] += t2[q];
      }
    }
  }
  for (int q = 0; q < n; ++q)
    if (state[q] == 2) scalar(q);
}

}  // namespace dlmfsi
