#include "integrate_batch.hpp"

#include <string>

#include "coupling.hpp"
#include "errors.hpp"

namespace dlmfsi {

BatchIntegrator::BatchIntegrator(const Integrand& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), affine_rule_(triangle_rule(integrand.product_degree)),
      gradients_(integrand.c1 != 0),
      constant_multiplier_gradients_(gradients_ && integrand.multiplier.degree() <= 1),
      fluid_functions_(integrand.fluid.functions().size()),
      multiplier_functions_(integrand.multiplier.functions().size()) {}

void BatchIntegrator::integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) {
  const size_t n = gather(image, kf, piece);
  counts_.points += static_cast<long>(n);
  const bool twins = integrand_.fluid.shared(kf) && integrand_.multiplier.shared(image.triangle.k);
  evaluate(image.triangle, kf, n, twins);
  add_sums(n, twins, block);
}

size_t BatchIntegrator::gather(const ClippedImage& image, int kf, const Piece& piece) {
  const MappedTriangle& mt = image.triangle;
  const auto& rule = mt.affine ? affine_rule_ : triangle_rule(image.degree);
  Point eta_corner[Piece::kMaxVertices], xi_corner[Piece::kMaxVertices];
  for (int v = 0; v < piece.n; ++v) {
    xi_corner[v] = image.guess(piece.v[v]);
    eta_corner[v] = integrand_.fluid.to_reference(kf, piece.v[v]);
  }
  if (!mt.affine) {
    std::array<double, 4> jacobian[Piece::kMaxVertices];  // not used
    mt.pull_back_points(piece.n, piece.v, xi_corner, jacobian, pull_back_scratch_);
  }
  const size_t n = static_cast<size_t>(piece.n - 2) * rule.size();
  if (weight_.size() < n) {
    weight_.resize(n);
    eta_.resize(n);
    xi_.resize(n);
    jacobian_.resize(n);
    fluid_values_.resize(3 * n * fluid_functions_);
    multiplier_values_.resize(3 * n * multiplier_functions_);
  }
  if (!mt.affine && y_.size() < n) y_.resize(n);
  size_t q = 0;
  for (int t = 1; t + 1 < piece.n; ++t) {
    const Point tri[3] = {piece.v[0], piece.v[t], piece.v[t + 1]};
    const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
    const Point et[3] = {eta_corner[0], eta_corner[t], eta_corner[t + 1]};
    const Point xt[3] = {xi_corner[0], xi_corner[t], xi_corner[t + 1]};
    for (const RulePoint& r : rule) {
      eta_[q] = from_reference(et, r.xi);
      xi_[q] = from_reference(xt, r.xi);
      if (mt.affine) {
        weight_[q] = area * r.weight / mt.affine_det;
      } else {
        y_[q] = from_reference(tri, r.xi);
        weight_[q] = area * r.weight;  // divided by det dX/ds below
      }
      ++q;
    }
  }
  if (mt.affine) return n;
  mt.pull_back_points(static_cast<int>(n), y_.data(), xi_.data(), jacobian_.data(), pull_back_scratch_);
  for (q = 0; q < n; ++q) {
    const std::array<double, 4>& j = jacobian_[q];
    const double det = j[0] * j[3] - j[1] * j[2];
    if (!(det > 0)) throw Error("the map folds solid triangle " + std::to_string(mt.k));
    weight_[q] /= det;
  }
  return n;
}

void BatchIntegrator::evaluate(const MappedTriangle& mt, int kf, size_t n, bool twins) {
  double* fv = fluid_values_.data();
  double* sv = multiplier_values_.data();
  const size_t fn = n * fluid_functions_, sn = n * multiplier_functions_;
  const int points = static_cast<int>(n);
  integrand_.fluid.evaluate_points(kf, eta_.data(), points, fv, gradients_ ? fv + fn : nullptr,
                                   gradients_ ? fv + 2 * fn : nullptr);
  if (constant_multiplier_gradients_) {
    // values at every point, the gradients (constant on the triangle) at the first
    constant_gradients_.resize(3 * multiplier_functions_);
    double* g = constant_gradients_.data();
    integrand_.multiplier.evaluate_points(mt.k, xi_.data(), points, sv, nullptr, nullptr);
    integrand_.multiplier.evaluate_points(mt.k, xi_.data(), 1, g + 2 * multiplier_functions_, g,
                                          g + multiplier_functions_);
  } else {
    integrand_.multiplier.evaluate_points(mt.k, xi_.data(), points, sv, gradients_ ? sv + sn : nullptr,
                                          gradients_ ? sv + 2 * sn : nullptr);
  }
  // Fluid values and chain-rule gradients with the weights folded in (those the sums read).
  const std::vector<char>& read = twins ? integrand_.pairs.fluid_read_by_sources() : integrand_.pairs.fluid_read();
  const double c1 = integrand_.c1, c2 = integrand_.c2;
  const double(&aj)[2][2] = mt.affine_value.jac;
  const std::array<double, 4> affine_jacobian{aj[0][0], aj[0][1], aj[1][0], aj[1][1]};
  if (constant_multiplier_gradients_) gradient_sums_.resize(2 * fluid_functions_);
  for (size_t f = 0; f < fluid_functions_; ++f) {
    if (!read[f]) continue;
    double* v = fv + f * n;
    for (size_t k = 0; k < n; ++k) v[k] *= c2 * weight_[k];
    if (!gradients_) continue;
    double *gx = fv + fn + f * n, *gy = fv + 2 * fn + f * n;
    double sx = 0, sy = 0;
    for (size_t k = 0; k < n; ++k) {
      // grad_s (phi o X)_b = sum_a d_a phi dX_a/ds_b, jacobian = (dX_0/ds_0, dX_0/ds_1, dX_1/ds_0, dX_1/ds_1)
      const std::array<double, 4>& jac = mt.affine ? affine_jacobian : jacobian_[k];
      const double w = c1 * weight_[k];
      const double g0 = w * (gx[k] * jac[0] + gy[k] * jac[2]), g1 = w * (gx[k] * jac[1] + gy[k] * jac[3]);
      if (constant_multiplier_gradients_) {
        sx += g0;
        sy += g1;
      } else {
        gx[k] = g0;
        gy[k] = g1;
      }
    }
    if (constant_multiplier_gradients_) {
      gradient_sums_[2 * f] = sx;
      gradient_sums_[2 * f + 1] = sy;
    }
  }
}

void BatchIntegrator::add_sums(size_t n, bool twins, LocalBlock& block) {
  const double* fv = fluid_values_.data();
  const double* sv = multiplier_values_.data();
  const size_t fn = n * fluid_functions_, sn = n * multiplier_functions_;
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    if (twins && pair.source >= 0) continue;  // added with its source
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      const double* phi = fv + static_cast<size_t>(pair.fluid_functions[a]) * n;
      for (size_t b = 0; b < pair.solid_functions.size(); ++b) {
        const double* psi = sv + static_cast<size_t>(pair.solid_functions[b]) * n;
        double sum = 0;
        for (size_t k = 0; k < n; ++k) sum += psi[k] * phi[k];
        if (constant_multiplier_gradients_) {
          // sum_k grad psi . g_k = grad psi . sum_k g_k (g: the fluid function's weighted gradients)
          const int f = pair.fluid_functions[a], m = pair.solid_functions[b];
          const double* g = constant_gradients_.data();
          sum += g[m] * gradient_sums_[2 * f] + g[multiplier_functions_ + m] * gradient_sums_[2 * f + 1];
        } else if (gradients_) {
          const double *px = psi + sn, *py = psi + 2 * sn, *gx = phi + fn, *gy = phi + 2 * fn;
          for (size_t k = 0; k < n; ++k) sum += px[k] * gx[k] + py[k] * gy[k];
        }
        block.column(pair.fluid_first + static_cast<int>(a))[pair.solid_first + static_cast<int>(b)] += sum;
        if (!twins) continue;
        for (int copy : pair.copies) {
          const ComponentPair& other = pairs[copy];
          block.column(other.fluid_first + static_cast<int>(a))[other.solid_first + static_cast<int>(b)] += sum;
        }
      }
    }
  }
}

}  // namespace dlmfsi
