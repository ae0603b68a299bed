#include "fe/points_evaluation3d.hpp"

#include <algorithm>
#include <vector>

#include "fe/lattice3d.hpp"
#include "fe/weighted_sum.hpp"

namespace dlmfsi {

namespace {

// The rows >= 4 to form so that the rows marked in need are formed (need closed under monomial_parents3: a
// parent's index is below its child's; need is changed), ascending.
std::vector<int> rows_with_parents(std::vector<char>& need) {
  const auto& parents = monomial_parents3();
  for (int m = static_cast<int>(need.size()) - 1; m >= 4; --m)
    if (need[m]) need[parents[m].parent] = 1;
  std::vector<int> rows;
  for (int m = 4; m < static_cast<int>(need.size()); ++m)
    if (need[m]) rows.push_back(m);
  return rows;
}

}  // namespace

void PolynomialTerms3::set(int degree, const double* coef, std::size_t width) {
  degree_ = degree;
  width_ = width;
  const int nm = monomial_count3(degree);
  const auto& derivative = monomial_derivatives3(degree);
  const int nm1 = degree > 0 ? monomial_count3(degree - 1) : 0;
  constant_.assign(4 * width, 0.0);
  start_.assign(1, 0);
  monomial_.clear();
  coefficient_.clear();
  std::vector<double> e(3 * static_cast<std::size_t>(std::max(nm1, 1)));
  auto add_polynomial = [&](std::size_t slot, const double* c, int count) {
    constant_[slot] = c[0];
    for (int m = 1; m < count; ++m)
      if (c[m] != 0) {
        monomial_.push_back(m);
        coefficient_.push_back(c[m]);
      }
    start_.push_back(static_cast<int>(monomial_.size()));
  };
  for (std::size_t f = 0; f < width; ++f) {
    const double* c = coef + f * nm;
    add_polynomial(4 * f, c, nm);
    // d/dxi_i of monomial m is factor * (monomial index) of degree - 1: one term each
    std::fill(e.begin(), e.end(), 0.0);
    for (int m = 1; m < nm; ++m)
      for (int i = 0; i < 3; ++i)
        if (derivative[m].index[i] >= 0) e[i * nm1 + derivative[m].index[i]] = derivative[m].factor[i] * c[m];
    for (int i = 0; i < 3; ++i) {
      if (nm1 == 0) {
        start_.push_back(static_cast<int>(monomial_.size()));
        continue;
      }
      add_polynomial(4 * f + 1 + i, &e[i * nm1], nm1);
    }
  }
  // The monomial rows the sums read, with the rows they are formed from; and the monomials of degree - 1
  // whose weighted sums the derivatives read.
  std::vector<char> need(nm, 0), moment(std::max(nm1, 1), 0), value(nm, 0);
  for (std::size_t slot = 0; slot < constant_.size(); ++slot)
    for (int t = start_[slot]; t < start_[slot + 1]; ++t) {
      need[monomial_[t]] = 1;
      if (slot % 4 != 0) moment[monomial_[t]] = 1;
      else value[monomial_[t]] = 1;
    }
  // the same for the values alone (weighted_sums without the gradients)
  read_.clear();
  value_read_.clear();
  for (int m = 1; m < nm; ++m) {
    if (need[m]) read_.push_back(m);
    if (value[m]) value_read_.push_back(m);
  }
  rows_ = rows_with_parents(need);
  value_rows_ = rows_with_parents(value);
  moments_.assign(1, 0);
  for (int m = 1; m < nm1; ++m)
    if (moment[m]) moments_.push_back(m);
}

namespace {

// mono[m * n + p] = monomial m at xi[p], row by row: monomial 0 is 1, the degree-1 rows the coordinates,
// and each further one of `rows` (ascending, closed under parents) a row before it times one coordinate
// (monomial_parents3), so that every row is one product along the points. The other rows are not formed.
void monomial_rows3(int degree, const std::vector<int>& rows, const Point3* xi, int n, double* mono) {
  for (int p = 0; p < n; ++p) mono[p] = 1;
  if (degree == 0) return;
  double* x[3] = {mono + n, mono + 2 * static_cast<std::size_t>(n), mono + 3 * static_cast<std::size_t>(n)};
  for (int p = 0; p < n; ++p) {
    x[0][p] = xi[p].x;
    x[1][p] = xi[p].y;
    x[2][p] = xi[p].z;
  }
  const auto& parents = monomial_parents3();
  for (int m : rows) {
    const double* from = mono + static_cast<std::size_t>(parents[m].parent) * n;
    const double* factor = x[parents[m].axis];
    double* to = mono + static_cast<std::size_t>(m) * n;
    for (int p = 0; p < n; ++p) to[p] = from[p] * factor[p];
  }
}

// The rows of the twins (twin[f] >= 0, when twin is not null): row f of `stride` values a copy of row twin[f].
void copy_twins(const int* twin, std::size_t width, std::size_t stride, double* rows) {
  if (!twin) return;
  for (std::size_t f = 0; f < width; ++f)
    if (twin[f] >= 0) std::copy(rows + twin[f] * stride, rows + (twin[f] + 1) * stride, rows + f * stride);
}

// out[p] = constant + sum over the terms of coefficient * mono[monomial * n + p], term by term.
inline void sum_terms(double constant, const int* monomial, const double* coefficient, int terms, const double* mono,
                      int n, double* out) {
  for (int p = 0; p < n; ++p) out[p] = constant;
  for (int t = 0; t < terms; ++t) {
    const double cm = coefficient[t];
    const double* row = mono + static_cast<std::size_t>(monomial[t]) * n;
    for (int p = 0; p < n; ++p) out[p] += cm * row[p];
  }
}

}  // namespace

void PolynomialTerms3::prepare_moments() {
  const int d = degree_ + 1, nm = monomial_count3(d);
  times_.assign(3 * monomial_.size(), 0);
  std::vector<char> need(nm, 0);
  for (int m = 0; m < 4; ++m) need[m] = 1;
  for (std::size_t slot = 0; slot < constant_.size(); ++slot)
    for (int t = start_[slot]; t < start_[slot + 1]; ++t) {
      need[monomial_[t]] = 1;
      if (slot % 4 != 0) continue;  // a derivative: its own monomial only
      int a, b, c;
      monomial_exponents3(monomial_[t], a, b, c);
      const int times[3] = {monomial_index3(a + 1, b, c), monomial_index3(a, b + 1, c), monomial_index3(a, b, c + 1)};
      for (int k = 0; k < 3; ++k) {
        times_[3 * t + k] = times[k];
        need[times[k]] = 1;
      }
    }
  moment_list_.clear();
  for (int m = 0; m < nm; ++m)
    if (need[m]) moment_list_.push_back(m);
  moment_rows_ = rows_with_parents(need);
}

void PolynomialTerms3::moments(const Point3* xi, const double* weight, int n, double* moment) const {
  thread_local std::vector<double> scratch;
  const std::size_t size = static_cast<std::size_t>(monomial_count3(degree_ + 1)) * n;
  if (scratch.size() < size) scratch.resize(size);
  double* mono = scratch.data();
  monomial_rows3(degree_ + 1, moment_rows_, xi, n, mono);
  for (int m : moment_list_) moment[m] = weighted_sum(weight, mono + static_cast<std::size_t>(m) * n, n);
}

void PolynomialTerms3::integrate(const int* twin, const double* j, const double* moment, double* first,
                                 double* gradient_sum) const {
  for (std::size_t f = 0; f < width_; ++f) {
    if (twin && twin[f] >= 0) continue;  // copied below
    const std::size_t value = 4 * f;
    double* o = first + 4 * f;
    for (int k = 0; k < 4; ++k) o[k] = constant_[value] * moment[k];  // monomials 1, xi1, xi2, xi3
    for (int t = start_[value]; t < start_[value + 1]; ++t) {
      const double c = coefficient_[t];
      o[0] += c * moment[monomial_[t]];
      for (int k = 0; k < 3; ++k) o[1 + k] += c * moment[times_[3 * t + k]];
    }
    double r[3];
    for (int i = 0; i < 3; ++i) {
      const std::size_t slot = value + 1 + i;
      double sum = constant_[slot] * moment[0];
      for (int t = start_[slot]; t < start_[slot + 1]; ++t) sum += coefficient_[t] * moment[monomial_[t]];
      r[i] = sum;
    }
    for (int a = 0; a < 3; ++a) gradient_sum[3 * f + a] = r[0] * j[a] + r[1] * j[3 + a] + r[2] * j[6 + a];
  }
  copy_twins(twin, width_, 4, first);
  copy_twins(twin, width_, 3, gradient_sum);
}

void PolynomialTerms3::evaluate(const int* twin, const double* j, const Point3* xi, int n, double* value,
                                double* gradient) const {
  const int nm = monomial_count3(degree_);
  // Monomial-major: mono[m * n + p] is monomial m at point p, so that each sum runs along the points.
  thread_local std::vector<double> scratch, reference;
  if (scratch.size() < static_cast<std::size_t>(nm) * n) scratch.resize(static_cast<std::size_t>(nm) * n);
  if (gradient && reference.size() < 3 * static_cast<std::size_t>(n)) reference.resize(3 * static_cast<std::size_t>(n));
  double* mono = scratch.data();
  monomial_rows3(degree_, rows_, xi, n, mono);
  auto sum = [&](std::size_t slot, double* out) {
    const int s = start_[slot], e = start_[slot + 1];
    sum_terms(constant_[slot], monomial_.data() + s, coefficient_.data() + s, e - s, mono, n, out);
  };
  for (std::size_t f = 0; f < width_; ++f) {
    if (twin && twin[f] >= 0) continue;  // copied below
    sum(4 * f, value + f * n);
    if (!gradient) continue;
    double* r[3] = {reference.data(), reference.data() + n, reference.data() + 2 * n};
    for (int i = 0; i < 3; ++i) sum(4 * f + 1 + i, r[i]);
    // d phi / d x_a = sum_i d phi / d xi_i  d xi_i / d x_a
    for (int a = 0; a < 3; ++a) {
      double* g = gradient + (3 * f + a) * n;
      for (int p = 0; p < n; ++p) g[p] = r[0][p] * j[a] + r[1][p] * j[3 + a] + r[2][p] * j[6 + a];
    }
  }
  copy_twins(twin, width_, n, value);
  if (gradient) copy_twins(twin, width_, 3 * static_cast<std::size_t>(n), gradient);
}

void PolynomialTerms3::evaluate_gradient_sums(const int* twin, const double* j, const Point3* xi, const double* weight,
                                              int n, double* value, double* gradient_sum) const {
  const int nm = monomial_count3(degree_), nm1 = degree_ > 0 ? monomial_count3(degree_ - 1) : 0;
  thread_local std::vector<double> scratch, moment;
  if (scratch.size() < static_cast<std::size_t>(nm) * n) scratch.resize(static_cast<std::size_t>(nm) * n);
  const std::size_t moments = static_cast<std::size_t>(std::max(nm1, 1));
  if (moment.size() < moments) moment.resize(moments);
  double* mono = scratch.data();
  monomial_rows3(degree_, rows_, xi, n, mono);
  // M_m for the monomials of degree - 1 that the derivatives read (M_0 = the sum of the weights)
  for (int m : moments_) moment[m] = weighted_sum(weight, mono + static_cast<std::size_t>(m) * n, n);
  for (std::size_t f = 0; f < width_; ++f) {
    if (twin && twin[f] >= 0) continue;  // copied below
    const int s = start_[4 * f], e = start_[4 * f + 1];
    sum_terms(constant_[4 * f], monomial_.data() + s, coefficient_.data() + s, e - s, mono, n, value + f * n);
    double r[3];
    for (int i = 0; i < 3; ++i) {
      const std::size_t slot = 4 * f + 1 + i;
      double sum = constant_[slot] * moment[0];
      for (int t = start_[slot]; t < start_[slot + 1]; ++t) sum += coefficient_[t] * moment[monomial_[t]];
      r[i] = sum;
    }
    for (int a = 0; a < 3; ++a) gradient_sum[3 * f + a] = r[0] * j[a] + r[1] * j[3 + a] + r[2] * j[6 + a];
  }
  copy_twins(twin, width_, n, value);
  copy_twins(twin, width_, 3, gradient_sum);
}

void PolynomialTerms3::weighted_sums(const int* twin, const double* j, const Point3* xi, const double* weight,
                                     int count, int n, double* value_sum, double* gradient_sum) const {
  const int nm = monomial_count3(degree_);
  thread_local std::vector<double> scratch, moment;
  if (scratch.size() < static_cast<std::size_t>(nm) * n) scratch.resize(static_cast<std::size_t>(nm) * n);
  if (moment.size() < static_cast<std::size_t>(nm) * count) moment.resize(static_cast<std::size_t>(nm) * count);
  double* mono = scratch.data();
  monomial_rows3(degree_, gradient_sum ? rows_ : value_rows_, xi, n, mono);
  // M_km = sum_p weight_k[p] (monomial m)(p) for the monomials the terms read (M_k0: the weights' sum), as
  // products of rows
  const std::vector<int>& read = gradient_sum ? read_ : value_read_;
  const int nr = static_cast<int>(read.size()) + 1;
  thread_local std::vector<const double*> rows;
  thread_local std::vector<double> product;
  rows.resize(static_cast<std::size_t>(count + nr));
  product.resize(static_cast<std::size_t>(count) * nr);
  for (int k = 0; k < count; ++k) rows[k] = weight + static_cast<std::size_t>(k) * n;
  rows[count] = mono;
  for (int r = 1; r < nr; ++r) rows[count + r] = mono + static_cast<std::size_t>(read[r - 1]) * n;
  row_products(rows.data(), count, rows.data() + count, nr, n, product.data());
  for (int k = 0; k < count; ++k) {
    double* mk = moment.data() + static_cast<std::size_t>(k) * nm;
    const double* pk = product.data() + static_cast<std::size_t>(k) * nr;
    mk[0] = pk[0];
    for (int r = 1; r < nr; ++r) mk[read[r - 1]] = pk[r];
  }
  sums_from_moments(twin, j, moment.data(), count, value_sum, gradient_sum);
}

void PolynomialTerms3::sums_from_moments(const int* twin, const double* j, const double* moment, int count,
                                         double* value_sum, double* gradient_sum) const {
  const int nm = monomial_count3(degree_);
  auto sum = [&](std::size_t slot, const double* mk) {
    double s = constant_[slot] * mk[0];
    for (int t = start_[slot]; t < start_[slot + 1]; ++t) s += coefficient_[t] * mk[monomial_[t]];
    return s;
  };
  for (std::size_t f = 0; f < width_; ++f) {
    if (twin && twin[f] >= 0) continue;  // copied below
    for (int k = 0; k < count; ++k) {
      const double* mk = moment + static_cast<std::size_t>(k) * nm;
      value_sum[count * f + k] = sum(4 * f, mk);
      if (!gradient_sum) continue;
      const double r[3] = {sum(4 * f + 1, mk), sum(4 * f + 2, mk), sum(4 * f + 3, mk)};
      double* g = gradient_sum + 3 * (count * f + k);
      for (int a = 0; a < 3; ++a) g[a] = r[0] * j[a] + r[1] * j[3 + a] + r[2] * j[6 + a];
    }
  }
  copy_twins(twin, width_, count, value_sum);
  if (gradient_sum) copy_twins(twin, width_, 3 * static_cast<std::size_t>(count), gradient_sum);
}

void weighted_monomial_rows3(int degree, const Point3* r, const double* w, std::size_t n, double* rows) {
  if (degree == 2) {  // in one pass, each row its parent's times the same coordinate (monomial_parents3) as below
    for (std::size_t q = 0; q < n; ++q) {
      const double one = w ? w[q] : 1, x = r[q].x, y = r[q].y, z = r[q].z;
      const double rx = w ? one * x : x, ry = w ? one * y : y, rz = w ? one * z : z;
      rows[q] = one;
      rows[n + q] = rx;
      rows[2 * n + q] = ry;
      rows[3 * n + q] = rz;
      rows[4 * n + q] = rx * x;  // x^2, xy, y^2, xz, yz, z^2
      rows[5 * n + q] = ry * x;
      rows[6 * n + q] = ry * y;
      rows[7 * n + q] = rz * x;
      rows[8 * n + q] = rz * y;
      rows[9 * n + q] = rz * z;
    }
    return;
  }
  for (std::size_t q = 0; q < n; ++q) rows[q] = w ? w[q] : 1;
  if (degree == 0) return;
  for (std::size_t q = 0; q < n; ++q) {
    rows[n + q] = w ? w[q] * r[q].x : r[q].x;
    rows[2 * n + q] = w ? w[q] * r[q].y : r[q].y;
    rows[3 * n + q] = w ? w[q] * r[q].z : r[q].z;
  }
  const auto& parents = monomial_parents3();
  for (int m = 4; m < monomial_count3(degree); ++m) {
    const double* from = rows + parents[m].parent * n;
    double* to = rows + m * n;
    const int axis = parents[m].axis;
    for (std::size_t q = 0; q < n; ++q) to[q] = from[q] * (axis == 0 ? r[q].x : axis == 1 ? r[q].y : r[q].z);
  }
}

void weighted_sums_polynomials3(int degree, const double* coef, std::size_t width, const double* j, const Point3* xi,
                                const double* weight, int count, int n, double* value_sum, double* gradient_sum) {
  thread_local PolynomialTerms3 terms;
  terms.set(degree, coef, width);
  terms.weighted_sums(nullptr, j, xi, weight, count, n, value_sum, gradient_sum);
}

void sums_from_moments_polynomials3(int degree, const double* coef, std::size_t width, const double* j,
                                    const double* moment, int count, double* value_sum, double* gradient_sum) {
  thread_local PolynomialTerms3 terms;
  terms.set(degree, coef, width);
  terms.sums_from_moments(nullptr, j, moment, count, value_sum, gradient_sum);
}

void evaluate_polynomials3_gradient_sums(int degree, const double* coef, std::size_t width, const double* j,
                                         const Point3* xi, const double* weight, int n, double* value,
                                         double* gradient_sum) {
  thread_local PolynomialTerms3 terms;
  terms.set(degree, coef, width);
  terms.evaluate_gradient_sums(nullptr, j, xi, weight, n, value, gradient_sum);
}

void evaluate_polynomials3(int degree, const double* coef, std::size_t width, const int* twin, const double* j,
                           const Point3* xi, int n, double* value, double* gradient) {
  thread_local PolynomialTerms3 terms;
  terms.set(degree, coef, width);
  terms.evaluate(twin, j, xi, n, value, gradient);
}

}  // namespace dlmfsi
