// How the image of a solid triangle under X differs from its image under A, the affine map that takes the
// reference corners (0, 0), (1, 0), (0, 1) to the corner images.
#pragma once
#include <algorithm>
#include <cmath>

#include "map/element_map.hpp"

namespace dlmfsi {

struct MapShape {
  bool affine = true;    // X agrees with A (to round-off)
  bool straight = true;  // the image's edges are straight segments (e.g. P1b: the bubble vanishes on edges)
  // How far X is from affine: the largest || A^-1 dX/dxi - I || (rows' absolute sums) over sample points.
  // 0 for an affine map; the map folds where it reaches 1 in some direction (2 for a P1b bubble moved 4/9
  // of the way to a corner).
  double nonlinearity = 0;
};

// The shape of X on the triangle of map, sampled at edge and interior points; image: the corner images,
// image_inv = A^-1 (d xi / d y), magnitude: the largest |coordinate| of the corner images (the round-off
// of X scales with it). Throws Error where X is NaN or Inf.
MapShape map_shape(const TriangleMap& map, const Point image[3], const double image_inv[2][2], double magnitude);

// The nonlinearity of X on the sub-triangle of reference corners ref whose images are img, sampled at its
// corners, edge midpoints and centroid (A: the affine map from ref to img); 1e300 when img is not
// counter-clockwise.
double nonlinearity_on(const TriangleMap& map, const Point ref[3], const Point img[3]);

// || a_inv [d1 d2] - I || (rows' absolute sums), 1e300 when not finite.
inline double jacobian_variation(const double a_inv[2][2], Point d1, Point d2) {
  const double m00 = a_inv[0][0] * d1.x + a_inv[0][1] * d1.y - 1;
  const double m01 = a_inv[0][0] * d2.x + a_inv[0][1] * d2.y;
  const double m10 = a_inv[1][0] * d1.x + a_inv[1][1] * d1.y;
  const double m11 = a_inv[1][0] * d2.x + a_inv[1][1] * d2.y - 1;
  const double v = std::max(std::fabs(m00) + std::fabs(m01), std::fabs(m10) + std::fabs(m11));
  return std::isfinite(v) ? v : 1e300;
}

}  // namespace dlmfsi
