#include "map/split3d.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/predicates3d.hpp"
#include "map/pull_back3d.hpp"

namespace dlmfsi {

namespace {

// The inverse of the 3 x 3 matrix with columns e1, e2, e3 (rows (e2 x e3, e3 x e1, e1 x e2) / det); false
// when det is not positive.
bool inverse_of_columns(Point3 e1, Point3 e2, Point3 e3, double inv[3][3]) {
  const double det = dot(e1, cross(e2, e3));
  if (!(det > 0)) return false;
  const Point3 rows[3] = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
  for (int r = 0; r < 3; ++r) {
    inv[r][0] = rows[r].x / det;
    inv[r][1] = rows[r].y / det;
    inv[r][2] = rows[r].z / det;
  }
  return true;
}

struct Node {
  MapPart3 part;
  int depth;
};

}  // namespace

double nonlinearity_on(const MappedTet& mt, const Point3 xi[4], const Point3 y[4]) {
  // A^-1 = R F^-1 with R = [xi_i - xi_0], F = [y_i - y_0] (columns)
  double fi[3][3];
  if (!inverse_of_columns(y[1] - y[0], y[2] - y[0], y[3] - y[0], fi)) return 1e300;
  const Point3 r[3] = {xi[1] - xi[0], xi[2] - xi[0], xi[3] - xi[0]};
  double ai[3][3];  // ai[a][b] = sum_i r[i]_a fi[i][b]
  for (int b = 0; b < 3; ++b) {
    ai[0][b] = r[0].x * fi[0][b] + r[1].x * fi[1][b] + r[2].x * fi[2][b];
    ai[1][b] = r[0].y * fi[0][b] + r[1].y * fi[1][b] + r[2].y * fi[2][b];
    ai[2][b] = r[0].z * fi[0][b] + r[1].z * fi[1][b] + r[2].z * fi[2][b];
  }
  // The corners, edge midpoints, face centroids and centroid, and points off these symmetric ones (a bubble's
  // gradient vanishes at all of those): barycentric (0.4, 0.2, 0.2, 0.2) and (0.1, 0.2, 0.3, 0.4) up to
  // cyclic order, and (0.5, 0.25, 0.25, 0) on each face.
  Point3 samples[27];
  int n = 0;
  auto at = [&](double l0, double l1, double l2, double l3) {
    samples[n++] = l0 * xi[0] + (l1 * xi[1] + (l2 * xi[2] + l3 * xi[3]));
  };
  for (int i = 0; i < 4; ++i) samples[n++] = xi[i];
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) samples[n++] = 0.5 * (xi[i] + xi[j]);
  const double third = 1.0 / 3;
  at(0, third, third, third);
  at(third, 0, third, third);
  at(third, third, 0, third);
  at(third, third, third, 0);
  at(0.25, 0.25, 0.25, 0.25);
  at(0.4, 0.2, 0.2, 0.2);
  at(0.2, 0.4, 0.2, 0.2);
  at(0.2, 0.2, 0.4, 0.2);
  at(0.2, 0.2, 0.2, 0.4);
  at(0.1, 0.2, 0.3, 0.4);
  at(0.4, 0.1, 0.2, 0.3);
  at(0.3, 0.4, 0.1, 0.2);
  at(0.2, 0.3, 0.4, 0.1);
  at(0, 0.5, 0.25, 0.25);
  at(0.25, 0, 0.5, 0.25);
  at(0.25, 0.25, 0, 0.5);
  at(0.5, 0.25, 0.25, 0);
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const Point3 s = samples[i];
    Point3 x, d[3];
    mt.reference_derivatives(s, x, d);
    for (int a = 0; a < 3; ++a) {
      double row = 0;
      for (int c = 0; c < 3; ++c) {
        const double m = ai[a][0] * d[c].x + ai[a][1] * d[c].y + ai[a][2] * d[c].z;
        row += std::fabs(m - (a == c ? 1 : 0));
      }
      worst = std::max(worst, std::isfinite(row) ? row : 1e300);
    }
  }
  return worst;
}

bool split_part3(const MappedTet& mt, const Point3 xi[4], const Point3 y[4], double target, int max_depth,
                 int max_parts, std::vector<MapPart3>& parts) {
  parts.clear();
  Node root;
  for (int i = 0; i < 4; ++i) {
    root.part.y[i] = y[i];
    root.part.xi[i] = xi[i];
  }
  root.part.nonlinearity = nonlinearity_on(mt, xi, y);
  root.depth = 0;
  std::vector<Node> stack{root};
  MapValue3 value;
  while (!stack.empty()) {
    const Node node = stack.back();
    stack.pop_back();
    const MapPart3& p = node.part;
    if (p.nonlinearity <= target) {
      parts.push_back(p);
      continue;
    }
    if (node.depth >= max_depth || static_cast<int>(parts.size() + stack.size()) + 8 > max_parts) return false;
    // The edge midpoints in y (mid[i][j], i < j) and their reference points.
    Point3 my[4][4], mx[4][4];
    for (int i = 0; i < 4; ++i) {
      my[i][i] = p.y[i];
      mx[i][i] = p.xi[i];
      for (int j = i + 1; j < 4; ++j) {
        my[i][j] = my[j][i] = 0.5 * (p.y[i] + p.y[j]);
        mx[i][j] = mx[j][i] = pull_back(mt, my[i][j], 0.5 * (p.xi[i] + p.xi[j]), value);
      }
    }
    // red refinement: the four corner tetrahedra and the inner octahedron cut along the diagonal (0-2)-(1-3)
    static const int kChildren[8][4][2] = {{{0, 0}, {0, 1}, {0, 2}, {0, 3}}, {{0, 1}, {1, 1}, {1, 2}, {1, 3}},
                                           {{0, 2}, {1, 2}, {2, 2}, {2, 3}}, {{0, 3}, {1, 3}, {2, 3}, {3, 3}},
                                           {{0, 1}, {0, 2}, {0, 3}, {1, 3}}, {{0, 1}, {0, 2}, {1, 2}, {1, 3}},
                                           {{0, 2}, {0, 3}, {1, 3}, {2, 3}}, {{0, 2}, {1, 2}, {1, 3}, {2, 3}}};
    for (const auto& child : kChildren) {
      Node c;
      c.depth = node.depth + 1;
      for (int v = 0; v < 4; ++v) {
        c.part.y[v] = my[child[v][0]][child[v][1]];
        c.part.xi[v] = mx[child[v][0]][child[v][1]];
      }
      if (orient3d(c.part.y[0], c.part.y[1], c.part.y[2], c.part.y[3]) < 0) {
        std::swap(c.part.y[2], c.part.y[3]);
        std::swap(c.part.xi[2], c.part.xi[3]);
      }
      c.part.nonlinearity = nonlinearity_on(mt, c.part.xi, c.part.y);
      stack.push_back(c);
    }
  }
  return true;
}

}  // namespace dlmfsi
