#include "map.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "errors.hpp"
#include "predicates.hpp"

namespace dlmfsi {

FieldMap::FieldMap(const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y, const double* coef_y,
                   int comp_y) {
  part_[0] = {&space_x, coef_x, comp_x, 0, 0};
  part_[1] = {&space_y, coef_y, comp_y, 0, 0};
  for (auto& p : part_) {
    if (p.comp < 0 || p.comp >= p.space->components()) throw Error("map component out of range");
    p.space->component_dofs(p.comp, p.first, p.last);
  }
}

void FieldMap::add(const Part& p, int k, Point xi, int a, MapValue& v) const {
  const int nd = p.space->local_dofs(), nc = p.space->components();
  // Small fixed buffers cover every FreeFEM 2D element used for maps; larger ones fall back to the heap.
  double stack_out[64 * 4 * 3];
  int stack_dofs[64];
  std::vector<double> heap_out;
  std::vector<int> heap_dofs;
  double* out = stack_out;
  int* dofs = stack_dofs;
  if (nd * nc * 3 > 64 * 4 * 3 || nd > 64) {
    heap_out.resize(static_cast<size_t>(nd) * nc * 3);
    heap_dofs.resize(nd);
    out = heap_out.data();
    dofs = heap_dofs.data();
  }
  p.space->evaluate(k, xi, out);
  p.space->dofs(k, dofs);
  double val = 0, dx = 0, dy = 0;
  for (int df = p.first; df < p.last; ++df) {
    const double c = p.coef[dofs[df]];
    const double* f = out + (df * nc + p.comp) * 3;
    val += c * f[0];
    dx += c * f[1];
    dy += c * f[2];
  }
  (a == 0 ? v.x.x : v.x.y) = val;
  v.jac[a][0] = dx;
  v.jac[a][1] = dy;
}

MapValue FieldMap::evaluate(int k, Point xi) const {
  MapValue v{};
  add(part_[0], k, xi, 0, v);
  add(part_[1], k, xi, 1, v);
  return v;
}

namespace {

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::string name(int k) { return "solid triangle " + std::to_string(k); }

}  // namespace

void MappedTriangle::prepare(const Mesh& solid_mesh, const SolidMap& map, int kk) {
  k = kk;
  solid_mesh.corners(k, solid);
  const Point ref[3] = {{0, 0}, {1, 0}, {0, 1}};
  for (int i = 0; i < 3; ++i) {
    image[i] = map.evaluate(k, ref[i]).x;
    if (!finite(image[i])) throw Error("the map is NaN or Inf at a corner of " + name(k));
  }
  const int o = orient2d(image[0], image[1], image[2]);
  if (o == 0) throw Error("the map flattens " + name(k) + " (its image has zero area)");
  if (o < 0) throw Error("the map inverts " + name(k) + " (its image is clockwise: a reflection or a fold)");

  // Compare X with the affine interpolant of the corner images at edge and interior points.
  const double scale = std::fabs(image[1].x - image[0].x) + std::fabs(image[1].y - image[0].y) +
                       std::fabs(image[2].x - image[0].x) + std::fabs(image[2].y - image[0].y);
  const double tol = 1e-13 * scale;
  const Point edge_points[6] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}, {0.25, 0}, {0.75, 0.25}, {0, 0.75}};
  const Point inner_points[3] = {{1.0 / 3, 1.0 / 3}, {0.2, 0.6}, {0.6, 0.15}};
  straight = true;
  affine = true;
  for (int e = 0; e < 6; ++e) {
    const Point x = map.evaluate(k, edge_points[e]).x;
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point line = from_reference(image, edge_points[e]);
    // Straight edge: the image point lies on the chord through the corner images (a parametrisation along
    // the chord that is not uniform is allowed).
    const Point a = image[e % 3], b = image[(e + 1) % 3];
    const Point ab = b - a;
    const double off = std::fabs(cross(ab, x - a)) / std::sqrt(ab.x * ab.x + ab.y * ab.y);
    if (off > tol) straight = false;
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) affine = false;
  }
  for (const Point& p : inner_points) {
    const Point x = map.evaluate(k, p).x;
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point line = from_reference(image, p);
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) affine = false;
  }
  if (affine) {
    // dX/ds = [image edges] [solid edges]^-1
    const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
    const Point f1 = image[1] - image[0], f2 = image[2] - image[0];
    const double d = cross(e1, e2);
    if (d <= 0) throw Error(name(k) + " is degenerate or clockwise in the solid mesh");
    affine_value.x = image[0];
    affine_value.jac[0][0] = (f1.x * e2.y - f2.x * e1.y) / d;
    affine_value.jac[0][1] = (f2.x * e1.x - f1.x * e2.x) / d;
    affine_value.jac[1][0] = (f1.y * e2.y - f2.y * e1.y) / d;
    affine_value.jac[1][1] = (f2.y * e1.x - f1.y * e2.x) / d;
    affine_det = det2(affine_value.jac);
    if (!(affine_det > 0)) throw Error("the map flattens " + name(k));
  }
}

Point MappedTriangle::pull_back(const SolidMap& map, Point y, MapValue& value) const {
  Point xi = to_reference(image, y);
  if (affine) {
    value = affine_value;
    value.x = y;
    return xi;
  }
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  for (int it = 0; it < 30; ++it) {
    value = map.evaluate(k, xi);
    // d X / d xi = jac * [e1 e2]
    const double a = value.jac[0][0] * e1.x + value.jac[0][1] * e1.y, b = value.jac[0][0] * e2.x + value.jac[0][1] * e2.y;
    const double c = value.jac[1][0] * e1.x + value.jac[1][1] * e1.y, d = value.jac[1][0] * e2.x + value.jac[1][1] * e2.y;
    const double det = a * d - b * c;
    if (!(det > 0)) throw Error("the map folds " + name(k) + " (jacobian determinant " + std::to_string(det) + ")");
    const Point r = y - value.x;
    const Point step{(d * r.x - b * r.y) / det, (a * r.y - c * r.x) / det};
    xi = xi + step;
    if (std::fabs(step.x) + std::fabs(step.y) < 1e-14) {
      value = map.evaluate(k, xi);
      return xi;
    }
  }
  throw Error("Newton's method did not converge pulling a point back into " + name(k));
}

}  // namespace dlmfsi
