// Both bases of the integrand at the points of a piece, evaluated all at once: for the f-th fitted function
// of either side its values at the n points and its physical gradients (component i at point q:
// gradient(f)[i * n + q]); through the element's own evaluation where a basis is not polynomial.
#pragma once
#include <vector>

#include "integration/integrator3d.hpp"

namespace dlmfsi {

class PointValues3 {
 public:
  explicit PointValues3(const Integrand3& integrand);

  // The bases at the n points: eta in fluid element kf, xi in solid element ks (reference coordinates).
  void evaluate(int kf, const Point3* eta, int ks, const Point3* xi, int n);
  // The same with the fluid gradients' weighted sums along the points (fluid_gradient_sum) in place of the
  // fluid gradients, for a fitted fluid basis and a multiplier fitted at degree 0 or 1, whose gradients
  // are then evaluated at the first point only (multiplier_constant_gradient).
  void evaluate_fluid_gradient_sums(int kf, const Point3* eta, const double* weight, int ks, const Point3* xi, int n);

  // The values at the n points and both sides' gradients at the first point only (both bases fitted at degree 0
  // or 1, their gradients constant on an element): fluid_constant_gradient, multiplier_constant_gradient.
  void evaluate_constant_gradients(int kf, const Point3* eta, int ks, const Point3* xi, int n);

  double* fluid_value(int f) { return &fluid_value_[static_cast<size_t>(f) * n_]; }
  // After evaluate_constant_gradients: the fluid function's gradient (x, y, z), the same at every point.
  const double* fluid_constant_gradient(int f) const { return &fluid_gradient_[3 * static_cast<size_t>(f)]; }
  double* fluid_gradient(int f) { return &fluid_gradient_[3 * static_cast<size_t>(f) * n_]; }
  const double* fluid_gradient_sum(int f) const { return &fluid_gradient_sum_[3 * static_cast<size_t>(f)]; }
  const double* multiplier_value(int g) const { return &multiplier_value_[static_cast<size_t>(g) * n_]; }
  const double* multiplier_gradient(int g) const { return &multiplier_gradient_[3 * static_cast<size_t>(g) * n_]; }
  // After evaluate_fluid_gradient_sums: the multiplier's gradient (x, y, z), the same at every point.
  const double* multiplier_constant_gradient(int g) const {
    return &multiplier_gradient_[3 * static_cast<size_t>(g)];
  }

 private:
  // n_ = n, and room for the values at n points and the gradients at gradient_points (n or 1) on both sides.
  void start(int n, int gradient_points);
  void evaluate_side(const PolynomialBasis3& poly, const Basis3& space, int k, const Point3* at, double* value,
                     double* gradient);

  const Integrand3& integrand_;
  bool gradients_;  // c1 != 0: the fitted gradients are needed
  int n_ = 0;
  std::vector<double> fluid_value_, fluid_gradient_, fluid_gradient_sum_, multiplier_value_, multiplier_gradient_,
      scratch_;
};

}  // namespace dlmfsi
