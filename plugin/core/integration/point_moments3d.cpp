#include "integration/point_moments3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "fe/lattice3d.hpp"
#include "fe/points_evaluation3d.hpp"
#include "fe/weighted_sum.hpp"

namespace dlmfsi {

namespace {

// times[b][j]: the index of monomial b times coordinate j (b of degree < kMaxLatticeDegree).
const std::vector<std::array<int, 3>>& monomial_times3() {
  static const auto table = [] {
    std::vector<std::array<int, 3>> all(monomial_count3(kMaxLatticeDegree - 1));
    for (int b = 0; b < static_cast<int>(all.size()); ++b) {
      int e[3];
      monomial_exponents3(b, e[0], e[1], e[2]);
      all[b] = {monomial_index3(e[0] + 1, e[1], e[2]), monomial_index3(e[0], e[1] + 1, e[2]),
                monomial_index3(e[0], e[1], e[2] + 1)};
    }
    return all;
  }();
  return table;
}

}  // namespace

void PointMoments3::reset(int m, int p, Point3 c) {
  m_ = m;
  p_ = p;
  cg_ = monomial_count3(m);
  cb_ = monomial_count3(p);
  c_ = c;
  moment_.resize(static_cast<std::size_t>(cg_) * cb_);
  clear();
}

void PointMoments3::clear() {
  std::fill(moment_.begin(), moment_.end(), 0.0);
  points_ = 0;
  n_ = 0;
}

void PointMoments3::grow() {
  const std::size_t size = std::max<std::size_t>(64, 2 * w_.size());
  xi_.resize(size);
  x_.resize(size);
  w_.resize(size);
}

template <int CG, int CB>
void PointMoments3::add_linear(std::size_t n, double to_unit) {
  double sum[CG * CB] = {};
  for (std::size_t q = 0; q < n; ++q) {
    const Point3 d = xi_[q] - c_, r = to_unit * (x_[q] - x_c_);
    const double w = w_[q];
    const double row_w[4] = {w, w * d.x, w * d.y, w * d.z}, row_r[4] = {1, r.x, r.y, r.z};
    for (int g = 0; g < CG; ++g)
      for (int b = 0; b < CB; ++b) sum[g * CB + b] += row_w[g] * row_r[b];
  }
  for (int i = 0; i < CG * CB; ++i) moment_[static_cast<std::size_t>(i)] += sum[i];
}

template <int P>
void PointMoments3::add_paired(std::size_t n, double to_unit) {
  typedef double Pair __attribute__((vector_size(16)));
  Pair acc[4][P] = {};  // [g][pair of monomials b]: (1, x), (y, z), then (x^2, xy), (y^2, xz), (yz, z^2)
  for (std::size_t q = 0; q < n; ++q) {
    const Point3 d = xi_[q] - c_, r = to_unit * (x_[q] - x_c_);
    const double w = w_[q];
    const double row_w[4] = {w, w * d.x, w * d.y, w * d.z};
    // the monomials as weighted_monomial_rows3 forms them: each its parent's times one coordinate
    Pair rb[P];
    rb[0] = Pair{1, r.x};
    rb[1] = Pair{r.y, r.z};
    if (P == 5) {
      rb[P - 3] = Pair{r.x * r.x, r.y * r.x};
      rb[P - 2] = Pair{r.y * r.y, r.z * r.x};
      rb[P - 1] = Pair{r.z * r.y, r.z * r.z};
    }
    for (int g = 0; g < 4; ++g)
      for (int b = 0; b < P; ++b) acc[g][b] += row_w[g] * rb[b];
  }
  for (int g = 0; g < 4; ++g)
    for (int b = 0; b < 2 * P; ++b) moment_[static_cast<std::size_t>(g * 2 * P + b)] += acc[g][b / 2][b % 2];
}

void PointMoments3::settle() {
  const std::size_t n = n_;
  if (n == 0) return;
  if (points_ == 0) {  // x_c: the points' mean; scale_: their largest distance from it along an axis
    Point3 sum;
    for (std::size_t q = 0; q < n; ++q) sum = sum + x_[q];
    x_c_ = (1.0 / static_cast<double>(n)) * sum;
    double spread = 0;
    for (std::size_t q = 0; q < n; ++q) {
      const Point3& x = x_[q];
      spread = std::max({spread, std::fabs(x.x - x_c_.x), std::fabs(x.y - x_c_.y), std::fabs(x.z - x_c_.z)});
    }
    scale_ = spread > 0 ? spread : 1;
  }
  const double to_unit = 1 / scale_;
  if ((m_ <= 1 && p_ <= 1) || (m_ == 1 && p_ == 2)) {  // a few products per point: summed point by point
    if (m_ == 1 && p_ == 2) add_paired<5>(n, to_unit);
    else if (m_ == 1 && p_ == 1) add_paired<2>(n, to_unit);
    else if (m_ == 1) add_linear<4, 1>(n, to_unit);
    else if (p_ == 1) add_linear<1, 4>(n, to_unit);
    else add_linear<1, 1>(n, to_unit);
    points_ += static_cast<long>(n);
    n_ = 0;
    return;
  }
  // rows: W_g = w (xi - c)^g (cg_ rows), then r^b (cb_ rows), r = (x - x_c) / L
  for (std::size_t q = 0; q < n; ++q) {
    xi_[q] = xi_[q] - c_;
    x_[q] = to_unit * (x_[q] - x_c_);
  }
  if (rows_.size() < static_cast<std::size_t>(cg_ + cb_) * n) rows_.resize(static_cast<std::size_t>(cg_ + cb_) * n);
  double* wr = rows_.data();
  double* br = wr + cg_ * n;
  weighted_monomial_rows3(m_, xi_.data(), w_.data(), n, wr);
  weighted_monomial_rows3(p_, x_.data(), nullptr, n, br);
  const double* x[monomial_count3(kMaxLatticeDegree)];
  const double* y[monomial_count3(kMaxLatticeDegree)];
  for (int g = 0; g < cg_; ++g) x[g] = wr + g * n;
  for (int b = 0; b < cb_; ++b) y[b] = br + b * n;
  if (product_.size() < static_cast<std::size_t>(cg_) * cb_) product_.resize(static_cast<std::size_t>(cg_) * cb_);
  row_products(x, cg_, y, cb_, static_cast<int>(n), product_.data());
  for (std::size_t i = 0; i < moment_.size(); ++i) moment_[i] += product_[i];
  points_ += static_cast<long>(n);
  n_ = 0;
}

void PointMoments3::element_moments(Point3 eta_c, const double* j, double* mu) const {
  expansion_.assign(static_cast<std::size_t>(cb_) * cb_, 0.0);
  double* t = expansion_.data();
  t[0] = 1;
  if (p_ > 0) {
    const double c[3] = {eta_c.x, eta_c.y, eta_c.z};
    for (int i = 0; i < 3; ++i) {  // eta_i = c_i + sum_k J_ik r_k
      double* row = t + (1 + i) * cb_;
      row[0] = c[i];
      for (int k = 0; k < 3; ++k) row[1 + k] = j[3 * i + k] * scale_;
    }
    const auto& parents = monomial_parents3();
    const auto& times = monomial_times3();
    const int below = monomial_count3(p_ - 1);  // the parents' terms are of degree < p
    for (int a = 4; a < cb_; ++a) {
      const double* from = t + parents[a].parent * cb_;
      const double* lin = t + (1 + parents[a].axis) * cb_;
      double* to = t + a * cb_;
      for (int b = 0; b < below; ++b) {
        const double f = from[b];
        if (f == 0) continue;
        to[b] += f * lin[0];
        for (int k = 0; k < 3; ++k) to[times[b][k]] += f * lin[1 + k];
      }
    }
  }
  for (int k = 0; k < cg_; ++k) {
    const double* m = moment_.data() + k * cb_;
    for (int a = 0; a < cb_; ++a) {
      const double* ta = t + a * cb_;
      double s = 0;
      for (int b = 0; b < cb_; ++b) s += ta[b] * m[b];
      mu[k * cb_ + a] = s;
    }
  }
}

}  // namespace dlmfsi
