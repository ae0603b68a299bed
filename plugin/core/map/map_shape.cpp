#include "map/map_shape.hpp"

#include <initializer_list>

#include "errors.hpp"

namespace dlmfsi {

namespace {

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

}  // namespace

MapShape map_shape(const TriangleMap& map, const Point image[3], const double image_inv[2][2], double magnitude) {
  // Compare X with A at edge and interior points. Round-off of the fit and of the map's own evaluation
  // scales with the coordinates, not the triangle.
  const double scale = std::fabs(image[1].x - image[0].x) + std::fabs(image[1].y - image[0].y) +
                       std::fabs(image[2].x - image[0].x) + std::fabs(image[2].y - image[0].y);
  const double tol = 1e-12 * scale + 1e-14 * magnitude;
  const Point edge_points[6] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}, {0.25, 0}, {0.75, 0.25}, {0, 0.75}};
  const Point inner_points[3] = {{1.0 / 3, 1.0 / 3}, {0.2, 0.6}, {0.6, 0.15}};
  // X and its reference derivatives at the corners, the edge points and the inner points (a fitted map: in
  // one evaluation of the 12 points; the same values as one by one)
  const Point corners[3] = {{0, 0}, {1, 0}, {0, 1}};
  auto sample = [&](int i) { return i < 3 ? corners[i] : (i < 9 ? edge_points[i - 3] : inner_points[i - 9]); };
  Point xs[12], d1s[12], d2s[12];
  bool evaluated = false;
  if (map.fitted()) {
    double xi1[12], xi2[12], v[6][12];
    for (int i = 0; i < 12; ++i) {
      const Point p = sample(i);
      xi1[i] = p.x;
      xi2[i] = p.y;
    }
    map.polynomial_points(12, xi1, xi2, v[0], v[1], v[2], v[3], v[4], v[5]);
    for (int i = 0; i < 12; ++i) {
      xs[i] = {v[0][i], v[1][i]};
      d1s[i] = {v[2][i], v[3][i]};
      d2s[i] = {v[4][i], v[5][i]};
    }
    evaluated = true;
  }
  auto value = [&](int i) { return evaluated ? xs[i] : map.at(sample(i)).x; };
  MapShape shape;
  for (int e = 0; e < 6; ++e) {
    const Point x = value(3 + e);
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + map.name());
    const Point line = from_reference(image, edge_points[e]);
    // Straight edge: the image point lies on the chord through the corner images (a parametrisation along
    // the chord that is not uniform is allowed).
    const Point a = image[e % 3], b = image[(e + 1) % 3];
    const Point ab = b - a;
    const double off = std::fabs(cross(ab, x - a)) / std::sqrt(ab.x * ab.x + ab.y * ab.y);
    if (off > tol) shape.straight = false;
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) shape.affine = false;
  }
  for (int i = 0; i < 3; ++i) {
    const Point x = value(9 + i);
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + map.name());
    const Point line = from_reference(image, inner_points[i]);
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) shape.affine = false;
  }
  if (shape.affine) return shape;
  // The jacobian's variation at the corners and the sample points (its extremes: at the corners for a P2
  // map, at the edge midpoints for a P1b bubble).
  for (int i = 0; i < 12; ++i) {
    Point x, d1 = d1s[i], d2 = d2s[i];
    if (!evaluated) map.reference_derivatives(sample(i), x, d1, d2);
    shape.nonlinearity = std::max(shape.nonlinearity, jacobian_variation(image_inv, d1, d2));
  }
  return shape;
}

double nonlinearity_on(const TriangleMap& map, const Point ref[3], const Point img[3]) {
  // A = F R^-1 with F = [img1 - img0, img2 - img0], R = [ref1 - ref0, ref2 - ref0], so A^-1 = R F^-1.
  const Point f1 = img[1] - img[0], f2 = img[2] - img[0], r1 = ref[1] - ref[0], r2 = ref[2] - ref[0];
  const double df = cross(f1, f2);
  if (!(df > 0)) return 1e300;
  const double fi[2][2] = {{f2.y / df, -f2.x / df}, {-f1.y / df, f1.x / df}};
  const double ai[2][2] = {{r1.x * fi[0][0] + r2.x * fi[1][0], r1.x * fi[0][1] + r2.x * fi[1][1]},
                           {r1.y * fi[0][0] + r2.y * fi[1][0], r1.y * fi[0][1] + r2.y * fi[1][1]}};
  const Point samples[7] = {ref[0], ref[1], ref[2], 0.5 * (ref[0] + ref[1]), 0.5 * (ref[1] + ref[2]),
                            0.5 * (ref[2] + ref[0]), (1.0 / 3) * (ref[0] + ref[1] + ref[2])};
  double worst = 0;
  for (const Point& xi : samples) {
    Point x, d1, d2;
    map.reference_derivatives(xi, x, d1, d2);
    worst = std::max(worst, jacobian_variation(ai, d1, d2));
  }
  return worst;
}

}  // namespace dlmfsi
