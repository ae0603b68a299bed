#include "integration/integrate_batch.hpp"

#include <string>

#include "sides/report.hpp"
#include "sides/sides.hpp"
#include "errors.hpp"
#include "fe/lattice.hpp"

namespace dlmfsi {

namespace {

// GCC would vectorize weighted_rows across two points (gathering each monomial's pair from two rows); with
// the loop over the points kept scalar, it packs the monomials' sums instead.
#if defined(__GNUC__) && !defined(__clang__)
#define DLMFSI_NO_LOOP_VECTORIZE __attribute__((optimize("no-tree-loop-vectorize")))
#else
#define DLMFSI_NO_LOOP_VECTORIZE
#endif

// The nm = monomial_count(d) monomials of degree <= d at the n points, point-major: rows[k * nm + m] (NM: nm
// when it is one of the constants below, the loops then unrolled; else 0).
template <int NM>
void monomial_rows(int d, const Point* at, size_t n, int nm, double* rows) {
  constexpr int kDegree = NM == 1 ? 0 : NM == 3 ? 1 : NM == 6 ? 2 : NM == 10 ? 3 : -1;
  const int degree = kDegree >= 0 ? kDegree : d;
  const int count = NM > 0 ? NM : nm;
  for (size_t k = 0; k < n; ++k) {
    double v[monomial_count(kMaxLatticeDegree)];
    monomial_values(degree, at[k], v);
    for (int m = 0; m < count; ++m) rows[k * count + m] = v[m];
  }
}

void monomial_rows(int d, const Point* at, size_t n, int nm, double* rows) {
  switch (nm) {
    case 1: monomial_rows<1>(d, at, n, nm, rows); break;
    case 3: monomial_rows<3>(d, at, n, nm, rows); break;
    case 6: monomial_rows<6>(d, at, n, nm, rows); break;
    case 10: monomial_rows<10>(d, at, n, nm, rows); break;
    default: monomial_rows<0>(d, at, n, nm, rows); break;
  }
}

// out[j * count + m] = sum_k weight[j * n + k] rows[k * stride + m] for the W weight rows j and m < count
// (NM: count when constant, else 0); each sum along k in order. W = 4 keeps 4 x 6 sums in registers.
template <int NM, int W>
DLMFSI_NO_LOOP_VECTORIZE void weighted_rows(const double* rows, size_t n, int stride, int count, const double* weight,
                                            double* out) {
  const int c = NM > 0 ? NM : count;
  double acc[W][NM > 0 ? NM : monomial_count(kMaxLatticeDegree)] = {};
  for (size_t k = 0; k < n; ++k) {
    const double* row = rows + k * stride;
#pragma GCC unroll 4
    for (int j = 0; j < W; ++j) {
      const double w = weight[j * n + k];
#pragma GCC unroll 10
      for (int m = 0; m < c; ++m) acc[j][m] += w * row[m];
    }
  }
  for (int j = 0; j < W; ++j)
    for (int m = 0; m < c; ++m) out[j * c + m] = acc[j][m];
}

template <int W>
void weighted_rows(const double* rows, size_t n, int stride, int count, const double* weight, double* out) {
  switch (count) {
    case 1: weighted_rows<1, W>(rows, n, stride, count, weight, out); break;
    case 3: weighted_rows<3, W>(rows, n, stride, count, weight, out); break;
    case 6: weighted_rows<6, W>(rows, n, stride, count, weight, out); break;
    case 10: weighted_rows<10, W>(rows, n, stride, count, weight, out); break;
    default: weighted_rows<0, W>(rows, n, stride, count, weight, out); break;
  }
}

}  // namespace

BatchIntegrator::BatchIntegrator(const Integrand& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), affine_rule_(triangle_rule(integrand.product_degree)),
      gradients_(integrand.c1 != 0),
      constant_multiplier_gradients_(gradients_ && integrand.multiplier.degree() <= 1),
      fluid_functions_(integrand.fluid.functions().size()),
      multiplier_functions_(integrand.multiplier.functions().size()) {
  by_moments_ = !gradients_ || constant_multiplier_gradients_;
  fluid_terms_ = integrand.fluid.terms();
  fluid_gradient_terms_ = monomial_count(integrand.fluid.degree() - 1);
}

double BatchIntegrator::integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) {
  add_gathered(image.triangle, kf, gather(image, kf, piece), block);
  return piece.area();
}

void BatchIntegrator::integrate_points(const MappedTriangle& mt, int kf, size_t n, const Point* y, Point origin,
                                       const Point* xi, const double* weight,
                                       const std::array<double, 4>* jacobian, LocalBlock& block) {
  reserve(n);
  for (size_t q = 0; q < n; ++q) {
    eta_[q] = integrand_.fluid.to_reference(kf, y[q], origin);
    xi_[q] = xi[q];
    weight_[q] = weight[q];
    jacobian_[q] = jacobian[q];
  }
  add_gathered(mt, kf, n, block);
}

void BatchIntegrator::add_gathered(const MappedTriangle& mt, int kf, size_t n, LocalBlock& block) {
  counts_.points += static_cast<long>(n);
  const bool twins = integrand_.fluid.shared(kf) && integrand_.multiplier.shared(mt.k);
  if (by_moments_)
    moments(mt, kf, n, twins);
  else
    evaluate(mt, kf, n, twins);
  add_sums(kf, n, twins, block);
}

void BatchIntegrator::reserve(size_t n) {
  if (weight_.size() >= n) return;
  weight_.resize(n);
  eta_.resize(n);
  xi_.resize(n);
  jacobian_.resize(n);
  if (!by_moments_) fluid_values_.resize(3 * n * fluid_functions_);  // the moments read the fit instead
  multiplier_values_.resize(3 * n * multiplier_functions_);
}

size_t BatchIntegrator::gather(const ClippedImage& image, int kf, const Piece& piece) {
  const MappedTriangle& mt = image.triangle;
  const auto& rule = mt.affine ? affine_rule_ : triangle_rule(image.degree);
  Point eta_corner[Piece::kMaxVertices], xi_corner[Piece::kMaxVertices];
  for (int v = 0; v < piece.n; ++v) {
    xi_corner[v] = image.guess(piece.v[v]);
    eta_corner[v] = integrand_.fluid.to_reference(kf, piece.v[v], image.origin);  // the piece is relative to it
  }
  if (!mt.affine) {
    std::array<double, 4> jacobian[Piece::kMaxVertices];  // not used
    mt.pull_back_points(piece.n, piece.v, xi_corner, jacobian, pull_back_scratch_);
  }
  const size_t n = static_cast<size_t>(piece.n - 2) * rule.size();
  reserve(n);
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
  integrand_.fluid.evaluate_points(kf, eta_.data(), points, fv, fv + fn, fv + 2 * fn);
  integrand_.multiplier.evaluate_points(mt.k, xi_.data(), points, sv, sv + sn, sv + 2 * sn);
  // Fluid values and chain-rule gradients with the weights folded in (those the sums read).
  const std::vector<char>& read = twins ? integrand_.pairs.fluid_read_by_sources() : integrand_.pairs.fluid_read();
  const double c1 = integrand_.c1, c2 = integrand_.c2;
  const double(&aj)[2][2] = mt.affine_value.jac;
  const std::array<double, 4> affine_jacobian{aj[0][0], aj[0][1], aj[1][0], aj[1][1]};
  for (size_t f = 0; f < fluid_functions_; ++f) {
    if (!read[f]) continue;
    double* v = fv + f * n;
    for (size_t k = 0; k < n; ++k) v[k] *= c2 * weight_[k];
    double *gx = fv + fn + f * n, *gy = fv + 2 * fn + f * n;
    for (size_t k = 0; k < n; ++k) {
      // grad_s (phi o X)_b = sum_a d_a phi dX_a/ds_b, jacobian = (dX_0/ds_0, dX_0/ds_1, dX_1/ds_0, dX_1/ds_1)
      const std::array<double, 4>& jac = mt.affine ? affine_jacobian : jacobian_[k];
      const double w = c1 * weight_[k];
      const double g0 = w * (gx[k] * jac[0] + gy[k] * jac[2]), g1 = w * (gx[k] * jac[1] + gy[k] * jac[3]);
      gx[k] = g0;
      gy[k] = g1;
    }
  }
}

void BatchIntegrator::moments(const MappedTriangle& mt, int kf, size_t n, bool twins) {
  const PolynomialBasis& fluid = integrand_.fluid;
  const ComponentPairs& pairs = integrand_.pairs;
  const int nm = fluid_terms_, nm1 = fluid_gradient_terms_, points = static_cast<int>(n);
  monomials_.resize(n * static_cast<size_t>(nm));
  double* mono = monomials_.data();
  monomial_rows(fluid.degree(), eta_.data(), n, nm, mono);
  // the multiplier's constant gradients, at the first point
  const PolynomialBasis& multiplier = integrand_.multiplier;
  if (gradients_) {
    constant_gradients_.resize(3 * multiplier_functions_);
    double* g = constant_gradients_.data();
    multiplier.evaluate_points(mt.k, xi_.data(), 1, g + 2 * multiplier_functions_, g, g + multiplier_functions_);
  }
  // P_bm = sum_q c2 w_q psi_b(q) m(q)
  value_moments_.resize(multiplier_functions_ * nm);
  row_.resize(n);
  const double c1 = integrand_.c1, c2 = integrand_.c2;
  const bool linear = multiplier.degree() == 1;  // psi_b = d0 + d1 xi1 + d2 xi2, summed as evaluate_points does
  double* sv = multiplier_values_.data();
  if (!linear) multiplier.evaluate_points(mt.k, xi_.data(), points, sv, nullptr, nullptr);
  for (int b : twins ? pairs.multiplier_read_by_sources() : pairs.multiplier_read()) {
    if (linear) {
      const double* d = multiplier.coefficients(mt.k) + 3 * static_cast<size_t>(b);
      for (size_t k = 0; k < n; ++k) row_[k] = c2 * weight_[k] * (d[0] + d[1] * xi_[k].x + d[2] * xi_[k].y);
    } else {
      const double* psi = sv + static_cast<size_t>(b) * n;
      for (size_t k = 0; k < n; ++k) row_[k] = c2 * weight_[k] * psi[k];
    }
    weighted_rows<1>(mono, n, nm, nm, row_.data(), &value_moments_[static_cast<size_t>(b) * nm]);
  }
  if (!gradients_) return;
  // Q_(e,c)m = sum_q c1 w_q (d eta_e/dy dX/ds_c)(q) m(q) over the derivatives' monomials (the first nm1),
  // d eta/dy = j (rows e) and dX/ds = (dX_0/ds_0, dX_0/ds_1, dX_1/ds_0, dX_1/ds_1)
  const double* j = fluid.inverse_jacobian(kf);
  gradient_moments_.resize(4 * static_cast<size_t>(nm1));
  double* q = gradient_moments_.data();
  if (mt.affine) {
    const double(&a)[2][2] = mt.affine_value.jac;
    const double frame[4] = {j[0] * a[0][0] + j[1] * a[1][0], j[0] * a[0][1] + j[1] * a[1][1],
                             j[2] * a[0][0] + j[3] * a[1][0], j[2] * a[0][1] + j[3] * a[1][1]};
    for (size_t k = 0; k < n; ++k) row_[k] = c1 * weight_[k];
    weighted_rows<1>(mono, n, nm, nm1, row_.data(), q);
    for (int ec = 3; ec >= 0; --ec)
      for (int m = 0; m < nm1; ++m) q[ec * nm1 + m] = frame[ec] * q[m];
  } else {
    frame_.resize(4 * n);
    double *f00 = frame_.data(), *f01 = f00 + n, *f10 = f01 + n, *f11 = f10 + n;
    for (size_t k = 0; k < n; ++k) {
      const std::array<double, 4>& a = jacobian_[k];
      const double w = c1 * weight_[k];
      f00[k] = w * (j[0] * a[0] + j[1] * a[2]);
      f01[k] = w * (j[0] * a[1] + j[1] * a[3]);
      f10[k] = w * (j[2] * a[0] + j[3] * a[2]);
      f11[k] = w * (j[2] * a[1] + j[3] * a[3]);
    }
    weighted_rows<4>(mono, n, nm, nm1, frame_.data(), q);
  }
  // sum_q w_q grad phi_f dX/ds, component c = sum_e sum_m E_efm Q_(e,c)m
  const std::vector<char>& read = twins ? pairs.fluid_read_by_sources() : pairs.fluid_read();
  const double* e = fluid.derivative_coefficients(kf);
  gradient_sums_.resize(2 * fluid_functions_);
  for (size_t f = 0; f < fluid_functions_; ++f) {
    if (!read[f]) continue;
    const double *e1 = e + f * 2 * nm1, *e2 = e1 + nm1;
    for (int c = 0; c < 2; ++c) {
      double sum = 0;
      for (int m = 0; m < nm1; ++m) sum += e1[m] * q[c * nm1 + m] + e2[m] * q[(2 + c) * nm1 + m];
      gradient_sums_[2 * f + c] = sum;
    }
  }
}

void BatchIntegrator::add_sums(int kf, size_t n, bool twins, LocalBlock& block) {
  const double* fv = fluid_values_.data();
  const double* sv = multiplier_values_.data();
  const size_t fn = n * fluid_functions_, sn = n * multiplier_functions_;
  const double* coefficients = integrand_.fluid.coefficients(kf);
  const double* g = constant_gradients_.data();
  // the sum of pair entry (fluid function f, multiplier function m)
  auto sum_of = [&](int f, int m) {
    double sum = 0;
    if (by_moments_) {
      // sum_q c2 w_q psi_m phi_f = sum_t C_ft P_mt, sum_q c1 w_q grad psi_m . g_q = grad psi_m . sum_q g_q
      const double* c = coefficients + static_cast<size_t>(f) * fluid_terms_;
      const double* p = &value_moments_[static_cast<size_t>(m) * fluid_terms_];
      for (int t = 0; t < fluid_terms_; ++t) sum += c[t] * p[t];
      if (gradients_) sum += g[m] * gradient_sums_[2 * f] + g[multiplier_functions_ + m] * gradient_sums_[2 * f + 1];
      return sum;
    }
    const double* phi = fv + static_cast<size_t>(f) * n;
    const double* psi = sv + static_cast<size_t>(m) * n;
    const double *px = psi + sn, *py = psi + 2 * sn, *gx = phi + fn, *gy = phi + 2 * fn;
    for (size_t k = 0; k < n; ++k) sum += psi[k] * phi[k];
    for (size_t k = 0; k < n; ++k) sum += px[k] * gx[k] + py[k] * gy[k];
    return sum;
  };
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    if (twins && pair.source >= 0) continue;  // added with its source
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      for (size_t b = 0; b < pair.solid_functions.size(); ++b) {
        const double sum = sum_of(pair.fluid_functions[a], pair.solid_functions[b]);
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
