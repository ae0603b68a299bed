#include "map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "errors.hpp"
#include "fold.hpp"
#include "lattice.hpp"
#include "polynomial_basis.hpp"
#include "polynomial_fit.hpp"
#include "predicates.hpp"

namespace dlmfsi {

int FieldMap::fit_degree(const Basis& space_x, int comp_x, const Basis& space_y, int comp_y) {
  int degree = 0;
  for (const auto& [space, comp] : {std::pair<const Basis*, int>{&space_x, comp_x}, {&space_y, comp_y}}) {
    if (comp < 0 || comp >= space->components()) throw Error("map component out of range");
    const int d = polynomial_degree(*space, {comp});
    if (d < 0) return -1;
    degree = std::max(degree, d);
  }
  return degree < 1 || degree > MappedTriangle::kMaxDegree ? -1 : degree;
}

FieldMap::FieldMap(const Mesh& solid, const Basis& space_x, const double* coef_x, int comp_x, const Basis& space_y,
                   const double* coef_y, int comp_y, const PolynomialBasis* fit_x, const PolynomialBasis* fit_y) {
  part_[0] = {&space_x, coef_x, comp_x, 0, 0};
  part_[1] = {&space_y, coef_y, comp_y, 0, 0};
  degree_ = fit_degree(space_x, comp_x, space_y, comp_y);
  for (auto& p : part_) p.space->component_dofs(p.comp, p.first, p.last);
  if (degree_ < 0) return;  // not polynomial (or constant): evaluate the map itself
  // X on triangle k = sum over the component's dofs of (dof value) * (basis polynomial).
  const int nm = monomial_count(degree_);
  monomial_coef_.assign(static_cast<size_t>(solid.size()) * 2 * nm, 0.0);
  std::unique_ptr<PolynomialBasis> own;
  const PolynomialBasis* fit = nullptr;
  for (int a = 0; a < 2; ++a) {
    const Part& p = part_[a];
    const PolynomialBasis* given = a == 0 ? fit_x : fit_y;
    if (given && given->degree() == degree_) {
      fit = given;
    } else if (a == 0 || p.space != part_[0].space || p.comp != part_[0].comp) {
      // X and Y are often the same space and component (two functions of one scalar space): one fit.
      own = std::make_unique<PolynomialBasis>(*p.space, solid, degree_, std::vector<int>{p.comp});
      fit = own.get();
    }
    const PolynomialBasis& poly = *fit;
    if (!poly.fitted()) {
      degree_ = -1;
      monomial_coef_.clear();
      return;
    }
    add_field_monomials(*p.space, p.coef, poly, nm, solid.size(), monomial_coef_, static_cast<size_t>(a) * nm,
                        2 * static_cast<size_t>(nm));
  }
}

bool FieldMap::coefficients(int k, double* cx, double* cy) const {
  if (monomial_coef_.empty()) return false;
  const int nm = monomial_count(degree_);
  const double* c = &monomial_coef_[static_cast<size_t>(k) * 2 * nm];
  std::copy(c, c + nm, cx);
  std::copy(c + nm, c + 2 * nm, cy);
  return true;
}

MapValue FieldMap::evaluate(int k, Point xi) const {
  MapValue v{};
  // X and Y are often two components of one vector function: evaluate that space once.
  const bool shared = part_[0].space == part_[1].space && part_[0].coef == part_[1].coef;
  thread_local std::vector<double> out;
  thread_local std::vector<int> dofs;
  for (int a = 0; a < 2; ++a) {
    const Part& p = part_[a];
    const int nc = p.space->components();
    if (a == 0 || !shared) {
      out.resize(static_cast<size_t>(p.space->local_dofs()) * nc * 3);
      dofs.resize(p.space->local_dofs());
      p.space->evaluate(k, xi, out.data());
      p.space->dofs(k, dofs.data());
    }
    double val = 0, dx = 0, dy = 0;
    for (int df = p.first; df < p.last; ++df) {
      const double c = p.coef[dofs[df]];
      const double* f = &out[(df * nc + p.comp) * 3];
      val += c * f[0];
      dx += c * f[1];
      dy += c * f[2];
    }
    (a == 0 ? v.x.x : v.x.y) = val;
    v.jac[a][0] = dx;
    v.jac[a][1] = dy;
  }
  return v;
}

namespace {

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::string name(int k) { return "solid triangle " + std::to_string(k); }

}  // namespace

namespace {

// X and its reference derivatives from the monomial coefficients; D >= 0 a constant degree (loops unrolled),
// D < 0 the run-time degree d.
template <int D>
void evaluate_polynomial(int d, const double* cx, const double* cy, Point xi, Point& x, Point& dx1, Point& dx2) {
  const int degree = D >= 0 ? D : d;
  double p1[MappedTriangle::kMaxDegree + 1], p2[MappedTriangle::kMaxDegree + 1];
  powers(degree, xi, p1, p2);
  // monomial m = xi1^a xi2^b in order of t = a + b, then b: d/dxi1 = a xi1^(a-1) xi2^b, d/dxi2 = b xi1^a xi2^(b-1).
  // Local sums: the outputs may alias memory the compiler cannot keep in registers.
  double x0 = cx[0], x1 = cy[0], a0 = 0, a1 = 0, b0 = 0, b1 = 0;
  int m = 1;
#pragma GCC unroll 8
  for (int t = 1; t <= degree; ++t) {
#pragma GCC unroll 8
    for (int b = 0; b <= t; ++b, ++m) {
      const int a = t - b;
      const double v = p1[a] * p2[b];
      x0 += cx[m] * v;
      x1 += cy[m] * v;
      if (a > 0) {
        const double g = a * p1[a - 1] * p2[b];
        a0 += cx[m] * g;
        a1 += cy[m] * g;
      }
      if (b > 0) {
        const double g = b * p1[a] * p2[b - 1];
        b0 += cx[m] * g;
        b1 += cy[m] * g;
      }
    }
  }
  x = {x0, x1};
  dx1 = {a0, a1};
  dx2 = {b0, b1};
}

}  // namespace

void MappedTriangle::polynomial(Point xi, Point& x, Point& dx1, Point& dx2) const {
  switch (degree_) {
    case 1: evaluate_polynomial<1>(1, cx_, cy_, xi, x, dx1, dx2); break;
    case 2: evaluate_polynomial<2>(2, cx_, cy_, xi, x, dx1, dx2); break;
    case 3: evaluate_polynomial<3>(3, cx_, cy_, xi, x, dx1, dx2); break;
    default: evaluate_polynomial<-1>(degree_, cx_, cy_, xi, x, dx1, dx2); break;
  }
}

MapValue MappedTriangle::at(Point xi) const {
  if (degree_ < 1) return map_->evaluate(k, xi);
  MapValue v;
  Point d1, d2;
  polynomial(xi, v.x, d1, d2);
  set_jacobian(d1, d2, v);
  return v;
}

void MappedTriangle::set_jacobian(Point d1, Point d2, MapValue& v) const {
  // dX/ds = dX/dxi (ds/dxi)^-1
  v.jac[0][0] = d1.x * inv_[0][0] + d2.x * inv_[1][0];
  v.jac[0][1] = d1.x * inv_[0][1] + d2.x * inv_[1][1];
  v.jac[1][0] = d1.y * inv_[0][0] + d2.y * inv_[1][0];
  v.jac[1][1] = d1.y * inv_[0][1] + d2.y * inv_[1][1];
}

void MappedTriangle::prepare(const Mesh& solid_mesh, const SolidMap& map, int kk) {
  k = kk;
  map_ = &map;
  solid_mesh.corners(k, solid);
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  const double ds = cross(e1, e2);
  if (!(ds > 0)) throw Error(name(k) + " is degenerate or clockwise in the solid mesh");
  // Products of the multiplier's gradients (1/h each) and of the area (h^2) stay normal numbers.
  if (ds < 0x1p-1010 || ds > 0x1p1010) {
    char s[160];
    std::snprintf(s, sizeof s, " has area %.3g: solid triangles from about 1e-150 to 1e150 in size are supported", 0.5 * ds);
    throw Error(name(k) + s);
  }
  inv_[0][0] = e2.y / ds;
  inv_[0][1] = -e2.x / ds;
  inv_[1][0] = -e1.y / ds;
  inv_[1][1] = e1.x / ds;

  degree_ = map.degree();
  if (degree_ > kMaxDegree) degree_ = -1;
  if (degree_ >= 1) {
    const int n = monomial_count(degree_);
    if (!map.coefficients(k, cx_, cy_)) {
      double vx[monomial_count(kMaxDegree)], vy[monomial_count(kMaxDegree)];
      for (int p = 0; p < n; ++p) {
        const Point x = map.evaluate(k, lattice_point(degree_, p)).x;
        vx[p] = x.x;
        vy[p] = x.y;
      }
      const auto& inv = vandermonde_inverse(degree_);
      for (int m = 0; m < n; ++m) {
        cx_[m] = cy_[m] = 0;
        for (int p = 0; p < n; ++p) {
          cx_[m] += inv[m * n + p] * vx[p];
          cy_[m] += inv[m * n + p] * vy[p];
        }
      }
    }
    for (int m = 0; m < n; ++m)
      if (!std::isfinite(cx_[m]) || !std::isfinite(cy_[m])) throw Error("the map is NaN or Inf in " + name(k));
  }
  const Point ref[3] = {{0, 0}, {1, 0}, {0, 1}};
  for (int i = 0; i < 3; ++i) {
    if (degree_ >= 1) {
      // At the corners every monomial but the powers of one coordinate vanishes: sum their coefficients
      // (monomial xi1^(t-b) xi2^b is number t(t+1)/2 + b).
      image[i] = {0, 0};
      for (int t = 0; t <= degree_; ++t) {
        const int m = t * (t + 1) / 2 + (i == 2 ? t : 0);
        if (t > 0 && i == 0) break;
        image[i] = image[i] + Point{cx_[m], cy_[m]};
      }
    } else {
      image[i] = map.evaluate(k, ref[i]).x;
    }
    if (!finite(image[i])) throw Error("the map is NaN or Inf at a corner of " + name(k));
  }
  const int o = orient2d(image[0], image[1], image[2]);
  if (o == 0) throw Error("the map flattens " + name(k) + " (its image has zero area)");
  if (o < 0) throw Error("the map inverts " + name(k) + " (its image is clockwise: a reflection or a fold)");

  {
    const Point f1 = image[1] - image[0], f2 = image[2] - image[0];
    const double di = cross(f1, f2);
    image_inv_[0][0] = f2.y / di;
    image_inv_[0][1] = -f2.x / di;
    image_inv_[1][0] = -f1.y / di;
    image_inv_[1][1] = f1.x / di;
  }
  if (degree_ == 1) {  // a P1 map: affine and straight by construction
    straight = affine = true;
    nonlinearity = 0;
  } else {
    classify();
    if (!affine) {
      check_fold();
      const double inv_norm = std::max(std::fabs(image_inv_[0][0]) + std::fabs(image_inv_[0][1]),
                                       std::fabs(image_inv_[1][0]) + std::fabs(image_inv_[1][1]));
      xi_round_off_ = 8 * kEps * magnitude() * inv_norm;
    }
  }
  if (affine) {
    // dX/ds = [image edges] [solid edges]^-1
    const Point f1 = image[1] - image[0], f2 = image[2] - image[0];
    affine_value.x = image[0];
    affine_value.jac[0][0] = (f1.x * e2.y - f2.x * e1.y) / ds;
    affine_value.jac[0][1] = (f2.x * e1.x - f1.x * e2.x) / ds;
    affine_value.jac[1][0] = (f1.y * e2.y - f2.y * e1.y) / ds;
    affine_value.jac[1][1] = (f2.y * e1.x - f1.y * e2.x) / ds;
    affine_det = det2(affine_value.jac);
    if (!(affine_det > 0)) throw Error("the map flattens " + name(k));
  }
}

void MappedTriangle::classify() {
  // Compare X with the affine interpolant of the corner images at edge and interior points.
  // Round-off of the fit and of the map's own evaluation scales with the coordinates, not the triangle.
  const double scale = std::fabs(image[1].x - image[0].x) + std::fabs(image[1].y - image[0].y) +
                       std::fabs(image[2].x - image[0].x) + std::fabs(image[2].y - image[0].y);
  const double tol = 1e-12 * scale + 1e-14 * magnitude();
  const Point edge_points[6] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}, {0.25, 0}, {0.75, 0.25}, {0, 0.75}};
  const Point inner_points[3] = {{1.0 / 3, 1.0 / 3}, {0.2, 0.6}, {0.6, 0.15}};
  straight = true;
  affine = true;
  for (int e = 0; e < 6; ++e) {
    const Point x = at(edge_points[e]).x;
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
    const Point x = at(p).x;
    if (!finite(x)) throw Error("the map is NaN or Inf inside " + name(k));
    const Point line = from_reference(image, p);
    if (std::fabs(x.x - line.x) + std::fabs(x.y - line.y) > tol) affine = false;
  }
  nonlinearity = 0;
  if (affine) return;
  // The jacobian's variation at the corners and the sample points (its extremes: at the corners for a P2
  // map, at the edge midpoints for a P1b bubble).
  const Point corners[3] = {{0, 0}, {1, 0}, {0, 1}};
  for (const Point* set : {corners, edge_points, inner_points}) {
    const int n = set == edge_points ? 6 : 3;
    for (int i = 0; i < n; ++i) nonlinearity = std::max(nonlinearity, jacobian_variation(set[i]));
  }
}

double MappedTriangle::jacobian_variation(Point xi) const {
  Point x, d1, d2;
  reference_derivatives(xi, x, d1, d2);
  // A^-1 [d1 d2] - I with A^-1 = image_inv_
  const double m00 = image_inv_[0][0] * d1.x + image_inv_[0][1] * d1.y - 1;
  const double m01 = image_inv_[0][0] * d2.x + image_inv_[0][1] * d2.y;
  const double m10 = image_inv_[1][0] * d1.x + image_inv_[1][1] * d1.y;
  const double m11 = image_inv_[1][0] * d2.x + image_inv_[1][1] * d2.y - 1;
  const double v = std::max(std::fabs(m00) + std::fabs(m01), std::fabs(m10) + std::fabs(m11));
  return std::isfinite(v) ? v : 1e300;
}

double MappedTriangle::nonlinearity_on(const Point ref[3], const Point img[3]) const {
  // A maps the sub-triangle's reference edges to its image edges: A = F R^-1, F = [img1 - img0, img2 - img0],
  // R = [ref1 - ref0, ref2 - ref0]; the variation is || A^-1 J - I || = || R F^-1 J - I ||.
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
    reference_derivatives(xi, x, d1, d2);
    const double m00 = ai[0][0] * d1.x + ai[0][1] * d1.y - 1, m01 = ai[0][0] * d2.x + ai[0][1] * d2.y;
    const double m10 = ai[1][0] * d1.x + ai[1][1] * d1.y, m11 = ai[1][0] * d2.x + ai[1][1] * d2.y - 1;
    const double v = std::max(std::fabs(m00) + std::fabs(m01), std::fabs(m10) + std::fabs(m11));
    worst = std::max(worst, std::isfinite(v) ? v : 1e300);
  }
  return worst;
}

double MappedTriangle::magnitude() const {
  double m = 0;
  for (const Point& p : image) m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
  return m;
}

double MappedTriangle::area_round_off(long pieces) const {
  double perimeter = 0;  // at most sqrt(2) times the perimeter: a bound suffices
  for (int i = 0; i < 3; ++i) perimeter += std::fabs(image[(i + 1) % 3].x - image[i].x) + std::fabs(image[(i + 1) % 3].y - image[i].y);
  return 8 * kEps * magnitude() * perimeter * static_cast<double>(pieces + 2);
}

void MappedTriangle::reference_derivatives(Point xi, Point& x, Point& d1, Point& d2) const {
  if (degree_ >= 1) {
    polynomial(xi, x, d1, d2);
    return;
  }
  const MapValue v = map_->evaluate(k, xi);
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  x = v.x;
  d1 = {v.jac[0][0] * e1.x + v.jac[0][1] * e1.y, v.jac[1][0] * e1.x + v.jac[1][1] * e1.y};
  d2 = {v.jac[0][0] * e2.x + v.jac[0][1] * e2.y, v.jac[1][0] * e2.x + v.jac[1][1] * e2.y};
}

void MappedTriangle::check_fold() const {
  auto det = [this](Point xi) {
    Point x, d1, d2;
    reference_derivatives(xi, x, d1, d2);
    return cross(d1, d2);  // the sign of det dX/ds (the solid triangle is counter-clockwise)
  };
  Point where;
  JacobianSign sign;
  if (degree_ >= 1) {
    sign = jacobian_sign(det, 2 * (degree_ - 1), 10, where);
  } else {
    // Not a polynomial: sampled on the degree-8 lattice.
    sign = JacobianSign::Positive;
    for (int p = 0; p < monomial_count(8) && sign == JacobianSign::Positive; ++p)
      if (!(det(lattice_point(8, p)) > 0)) {
        where = lattice_point(8, p);
        sign = JacobianSign::Folds;
      }
  }
  if (sign == JacobianSign::Positive) return;
  char at[120];
  std::snprintf(at, sizeof at, " at reference point (%.3g, %.3g)", where.x, where.y);
  if (sign == JacobianSign::Folds)
    throw Error("the map folds " + name(k) + " (its jacobian determinant is not positive" + at + ")");
  throw Error("the map nearly folds " + name(k) + " (its jacobian determinant comes within about 1e-6 of zero" + at +
              ")");
}

Point MappedTriangle::pull_back(Point y, MapValue& value) const {
  const Point xi = affine_reference(y);
  if (affine) {
    value = affine_value;
    value.x = y;
    return xi;
  }
  return pull_back(y, xi, value);
}

Point MappedTriangle::pull_back(Point y, Point xi, MapValue& value) const {
  if (affine) return pull_back(y, value);
  // Newton on X(xi) = y with dX/dxi = [d1 d2] (d1, d2: the derivatives in xi1, xi2); its determinant has
  // the sign of det dX/ds (the solid triangle is counter-clockwise).
  const bool fitted = degree_ >= 1;
  const Point e1 = solid[1] - solid[0], e2 = solid[2] - solid[0];
  auto evaluate = [&](Point at_xi, Point& x, Point& d1, Point& d2) {
    if (fitted) {
      polynomial(at_xi, x, d1, d2);
      return;
    }
    value = map_->evaluate(k, at_xi);
    x = value.x;
    d1 = {value.jac[0][0] * e1.x + value.jac[0][1] * e1.y, value.jac[1][0] * e1.x + value.jac[1][1] * e1.y};
    d2 = {value.jac[0][0] * e2.x + value.jac[0][1] * e2.y, value.jac[1][0] * e2.x + value.jac[1][1] * e2.y};
  };
  auto finish = [&](Point x, Point d1, Point d2) {
    if (!fitted) return;  // value already holds X and dX/ds there
    value.x = x;
    set_jacobian(d1, d2, value);
  };
  double previous = 1e300;
  Point last = xi, last_step{0, 0};  // the last iterate with a positive determinant, and the step from it
  for (int it = 0; it < 80; ++it) {
    Point x, d1, d2;
    evaluate(xi, x, d1, d2);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(det > 0)) {
      if (it == 0) throw Error("the map folds " + name(k) + " (jacobian determinant " + std::to_string(det) + ")");
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
    if (size < std::max(1e-12, xi_round_off_)) {
      finish(x, d1, d2);
      return xi;
    }
    // Stalled at the round-off floor (quadratic convergence would have halved the step).
    if (size < std::max(1e-9, 64 * xi_round_off_) && size > 0.5 * previous) {
      evaluate(xi, x, d1, d2);
      finish(x, d1, d2);
      return xi;
    }
    previous = size;
  }
  throw Error("Newton's method did not converge pulling a point back into " + name(k));
}

}  // namespace dlmfsi
