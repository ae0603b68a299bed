#include "integration/point_values3d.hpp"

#include <algorithm>

namespace dlmfsi {

namespace {

// At least size entries. The buffers are read through n_ (the accessors), so they only grow: resizing them to
// each call's n would zero-fill again whatever a smaller call had cut off (7 % of a curved 3D call, whose pieces
// carry very different numbers of points).
void grow(std::vector<double>& v, size_t size) {
  if (v.size() < size) v.resize(size);
}

}  // namespace

PointValues3::PointValues3(const Integrand3& integrand) : integrand_(integrand), gradients_(integrand.c1 != 0) {}

void PointValues3::start(int n, int gradient_points) {
  n_ = n;
  const size_t nn = static_cast<size_t>(n), ng = static_cast<size_t>(gradient_points);
  const size_t fluid_functions = integrand_.fluid.functions().size();
  const size_t multiplier_functions = integrand_.multiplier.functions().size();
  grow(fluid_value_, nn * fluid_functions);
  grow(fluid_gradient_, 3 * ng * fluid_functions);
  grow(multiplier_value_, nn * multiplier_functions);
  grow(multiplier_gradient_, 3 * ng * multiplier_functions);
  grow(scratch_, std::max(fluid_functions, multiplier_functions));
}

void PointValues3::evaluate(int kf, const Point3* eta, int ks, const Point3* xi, int n) {
  start(n, n);
  evaluate_side(integrand_.fluid, integrand_.fluid_space, kf, eta, fluid_value_.data(), fluid_gradient_.data());
  evaluate_side(integrand_.multiplier, integrand_.multiplier_space, ks, xi, multiplier_value_.data(),
                multiplier_gradient_.data());
}

void PointValues3::evaluate_fluid_gradient_sums(int kf, const Point3* eta, const double* weight, int ks,
                                                const Point3* xi, int n) {
  start(n, 1);
  grow(fluid_gradient_sum_, 3 * integrand_.fluid.functions().size());
  integrand_.fluid.evaluate_gradient_sums(kf, eta, weight, n, fluid_value_.data(), fluid_gradient_sum_.data());
  // the multiplier's values at the points, its (constant) gradients at the first
  integrand_.multiplier.evaluate_points(ks, xi, n, multiplier_value_.data(), nullptr);
  integrand_.multiplier.evaluate_points(ks, xi, 1, scratch_.data(), multiplier_gradient_.data());
}

void PointValues3::evaluate_constant_gradients(int kf, const Point3* eta, int ks, const Point3* xi, int n) {
  start(n, 1);
  integrand_.fluid.evaluate_points(kf, eta, n, fluid_value_.data(), nullptr);
  integrand_.fluid.evaluate_points(kf, eta, 1, scratch_.data(), fluid_gradient_.data());
  integrand_.multiplier.evaluate_points(ks, xi, n, multiplier_value_.data(), nullptr);
  integrand_.multiplier.evaluate_points(ks, xi, 1, scratch_.data(), multiplier_gradient_.data());
}

void PointValues3::evaluate_side(const PolynomialBasis3& poly, const Basis3& space, int k, const Point3* at,
                                 double* value, double* gradient) {
  const int n = n_;
  if (poly.fitted()) {
    poly.evaluate_points(k, at, n, value, gradients_ ? gradient : nullptr);
    return;
  }
  const int nc = space.components();
  grow(scratch_, static_cast<size_t>(space.local_dofs()) * nc * 4);
  const std::vector<int>& functions = poly.functions();
  for (int q = 0; q < n; ++q) {
    space.evaluate(k, at[q], scratch_.data());
    for (size_t f = 0; f < functions.size(); ++f) {
      const double* o = &scratch_[functions[f] * 4];
      value[f * n + q] = o[0];
      for (int i = 0; i < 3; ++i) gradient[(3 * f + i) * n + q] = o[1 + i];
    }
  }
}

}  // namespace dlmfsi
