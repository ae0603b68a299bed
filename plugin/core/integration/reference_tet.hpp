// The reference tetrahedron (corner 0 at the origin, corner i at e_i) and a quadratic map's second derivatives
// on it: small helpers of the reference side's integrators (integrate_points3d.cpp, side_band3d.cpp).
#pragma once
#include "point3.hpp"

namespace dlmfsi {

// lambda_i and grad lambda_i.
inline double barycentric(Point3 xi, int i) {
  return i == 0 ? 1 - xi.x - xi.y - xi.z : i == 1 ? xi.x : i == 2 ? xi.y : xi.z;
}
inline Point3 barycentric_gradient(int i) {
  return i == 0 ? Point3{-1, -1, -1} : i == 1 ? Point3{1, 0, 0} : i == 2 ? Point3{0, 1, 0} : Point3{0, 0, 1};
}

// The edges (i, k), i < k, numbered 0 to 5 in the order (0,1), (0,2), (0,3), (1,2), (1,3), (2,3).
inline int edge_index(int i, int k) { return i == 0 ? k - 1 : i == 1 ? k + 1 : 5; }

// The slope along w of a quadratic map's dX/dxi_i: (H w)_i, H[a][i][k] = d2 X_a / dxi_i dxi_k.
inline Point3 hessian_along(const double (&h)[3][3][3], int i, Point3 w) {
  return {h[0][i][0] * w.x + h[0][i][1] * w.y + h[0][i][2] * w.z,
          h[1][i][0] * w.x + h[1][i][1] * w.y + h[1][i][2] * w.z,
          h[2][i][0] * w.x + h[2][i][1] * w.y + h[2][i][2] * w.z};
}

// A quadratic map's second derivative along w: w^T H w = sum_i w_i (H w)_i.
inline Point3 hessian_twice(const double (&h)[3][3][3], Point3 w) {
  Point3 whw;
  for (int i = 0; i < 3; ++i) whw = whw + coordinate(w, i) * hessian_along(h, i, w);
  return whw;
}

}  // namespace dlmfsi
