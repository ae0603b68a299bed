#include "map/fold3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "errors.hpp"
#include "fe/lattice3d.hpp"
#include "fe/matrix_inverse.hpp"

namespace dlmfsi {

namespace {

struct BernsteinTable {
  std::vector<double> collocation;  // C, row-major
  std::vector<double> inverse;      // C^-1 as computed, row-major: Bernstein coefficients = inverse * values
  double amplification = 0;         // max_m sum_p |C^-1[m][p]|
};

// C[p][m] = B_m(lattice point p) for the Bernstein polynomials of degree n, the exponents (m1, m2, m3) of
// B_m those of monomial m (lattice3d.hpp) and m0 = n - m1 - m2 - m3; built once per degree, on first use.
const BernsteinTable& bernstein_table(int n) {
  static std::once_flag once[kMaxJacobianDegree3 + 1];
  static BernsteinTable table[kMaxJacobianDegree3 + 1];
  std::call_once(once[n], [n] {
    const int size = monomial_count3(n);
    std::vector<double> c(static_cast<size_t>(size) * size);
    auto factorial = [](int k) {
      double f = 1;
      for (int i = 2; i <= k; ++i) f *= i;
      return f;
    };
    for (int p = 0; p < size; ++p) {
      const Point3 x = lattice_point3(n, p);
      const double l[4] = {1 - x.x - x.y - x.z, x.x, x.y, x.z};
      for (int m = 0; m < size; ++m) {
        int e[4];
        monomial_exponents3(m, e[1], e[2], e[3]);
        e[0] = n - e[1] - e[2] - e[3];
        double b = factorial(n);
        for (int i = 0; i < 4; ++i) b *= std::pow(l[i], e[i]) / factorial(e[i]);
        c[static_cast<size_t>(p) * size + m] = b;
      }
    }
    BernsteinTable& t = table[n];
    t.inverse = inverse(c, size);
    t.collocation = std::move(c);
    for (int m = 0; m < size; ++m) {
      double row = 0;
      for (int p = 0; p < size; ++p) row += std::fabs(t.inverse[static_cast<size_t>(m) * size + p]);
      t.amplification = std::max(t.amplification, row);
    }
  });
  return table[n];
}

using Tet = std::array<Point3, 4>;

// Is the polynomial with lattice values v (each within round_off of the exact one) positive on the
// tetrahedron? b = C^-1 v as computed is the exact Bernstein coefficient vector of the polynomial Q with
// lattice values C b; the exact polynomial differs from Q by the one with lattice values v - C b, whose
// Bernstein coefficients are within kappa |v - C b|_max of zero. So min b_m > kappa (round_off +
// |v - C b|_max + the round-off of C b) proves it positive, whatever the error of the computed C^-1
// (C b is computed with error <= (size + 1) eps max|b|: the rows of C are non-negative and sum to one).
bool certified(const BernsteinTable& t, int size, const std::vector<double>& v, std::vector<double>& b,
               double round_off) {
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  for (int m = 0; m < size; ++m) {
    const double* row = &t.inverse[static_cast<size_t>(m) * size];
    double s = 0;
    for (int p = 0; p < size; ++p) s += row[p] * v[p];
    b[m] = s;
    smallest = std::min(smallest, s);
    largest = std::max(largest, std::fabs(s));
  }
  if (!(smallest > 2 * t.amplification * round_off)) return false;
  double residual = 0;
  for (int p = 0; p < size; ++p) {
    const double* row = &t.collocation[static_cast<size_t>(p) * size];
    double s = 0;
    for (int m = 0; m < size; ++m) s += row[m] * b[m];
    residual = std::max(residual, std::fabs(v[p] - s));
  }
  // (2 kappa: kappa as computed from the computed C^-1, within far less than a factor 2 of the exact one)
  const double eps = std::numeric_limits<double>::epsilon();
  return smallest > 2 * t.amplification * (round_off + residual + 2 * (size + 1) * eps * largest);
}

}  // namespace

double bernstein_amplification3(int n) {
  return bernstein_table(std::max(0, std::min(n, kMaxJacobianDegree3))).amplification;
}

JacobianSign jacobian_sign3(const std::function<DetSample(Point3)>& det, int n, int max_depth, int max_tetrahedra,
                            Point3& where, int* tested) {
  if (n < 0 || n > kMaxJacobianDegree3) throw Error("jacobian degree " + std::to_string(n) + " out of range");
  const int size = monomial_count3(n);
  const BernsteinTable& table = bernstein_table(n);
  std::vector<Point3> lattice(size);
  for (int p = 0; p < size; ++p) lattice[p] = lattice_point3(n, p);
  struct Sub {
    Tet q;
    int depth;
  };
  std::vector<Sub> stack{{Tet{Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0, 0, 1}}, 0}};
  std::vector<double> values(size), coefficients(size);
  JacobianSign result = JacobianSign::Positive;
  int count = 0;
  while (!stack.empty()) {
    const Sub s = stack.back();
    stack.pop_back();
    ++count;
    double round_off = 0;
    for (int p = 0; p < size; ++p) {
      const Point3 l = lattice[p];
      const Point3 xi = s.q[0] + (l.x * (s.q[1] - s.q[0]) + l.y * (s.q[2] - s.q[0]) + l.z * (s.q[3] - s.q[0]));
      const DetSample v = det(xi);
      if (!(v.value > 0)) {
        where = xi;
        if (tested) *tested = count;
        return JacobianSign::Folds;
      }
      values[p] = v.value;
      round_off = std::max(round_off, v.round_off);
    }
    if (certified(table, size, values, coefficients, round_off)) continue;
    if (s.depth >= max_depth || count + static_cast<int>(stack.size()) + 8 > max_tetrahedra) {
      if (result == JacobianSign::Positive) where = 0.25 * (s.q[0] + s.q[1] + s.q[2] + s.q[3]);
      result = JacobianSign::NearlyFolds;  // keep looking for a certain fold elsewhere
      if (count + static_cast<int>(stack.size()) + 8 > max_tetrahedra) break;
      continue;
    }
    const Tet& t = s.q;
    auto mid = [&](int i, int j) { return 0.5 * (t[i] + t[j]); };
    const Point3 m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3), m23 = mid(2, 3);
    const Tet children[8] = {{t[0], m01, m02, m03}, {m01, t[1], m12, m13}, {m02, m12, t[2], m23}, {m03, m13, m23, t[3]},
                             {m01, m02, m03, m13},  {m01, m02, m12, m13},  {m02, m03, m13, m23},  {m02, m12, m13, m23}};
    for (const Tet& c : children) stack.push_back({c, s.depth + 1});
  }
  if (tested) *tested = count;
  return result;
}


DetSample jacobian_det(const TetrahedronMap& mt, Point3 xi) {
  // d[i][a] = dX_a/dxi_i = sum_m c_a[m] f v_j, computed with an error <= (nm + degree + 1) eps A[i][a],
  // A[i][a] = sum_m |c_a[m] f v_j| >= |d[i][a]|; the triple product then errs by at most
  // ((1 + g)^3 - 1 + 4 eps) perm(A) with g that factor (perm: the permanent, the sum of the six
  // products of the determinant without signs).
  const int degree = mt.fitted_degree(), nm = monomial_count3(degree);
  const double* c[3] = {mt.coefficients(0), mt.coefficients(1), mt.coefficients(2)};
  double v[monomial_count3(TetrahedronMap::kMaxDegree)];
  monomial_values3(degree, xi, v);
  double d[3][3] = {}, a[3][3] = {};
  const auto& derivative = monomial_derivatives3(degree);
  for (int m = 0; m < nm; ++m)
    for (int i = 0; i < 3; ++i) {
      const int j = derivative[m].index[i];
      if (j < 0) continue;
      const double dm = derivative[m].factor[i] * v[j];
      for (int b = 0; b < 3; ++b) {
        d[i][b] += c[b][m] * dm;
        a[i][b] += std::fabs(c[b][m] * dm);
      }
    }
  const double det = det3(d);
  const double perm = a[0][0] * (a[1][1] * a[2][2] + a[1][2] * a[2][1]) +
                      a[0][1] * (a[1][0] * a[2][2] + a[1][2] * a[2][0]) +
                      a[0][2] * (a[1][0] * a[2][1] + a[1][1] * a[2][0]);
  const double eps = std::numeric_limits<double>::epsilon();
  return {det, 4 * (nm + degree + 3) * eps * perm};
}

void check_fold(const TetrahedronMap& mt) {
  Point3 where;
  JacobianSign sign = JacobianSign::Positive;
  if (mt.fitted_degree() >= 1) {
    sign = jacobian_sign3([&mt](Point3 xi) { return jacobian_det(mt, xi); }, 3 * (mt.fitted_degree() - 1), kFoldDepth,
                          kFoldTetrahedra, where);
  } else {
    // Not a polynomial: sampled on the degree-8 lattice.
    for (int p = 0; p < monomial_count3(8) && sign == JacobianSign::Positive; ++p) {
      Point3 x, d[3];
      mt.reference_derivatives(lattice_point3(8, p), x, d);
      if (!(dot(d[0], cross(d[1], d[2])) > 0)) {
        where = lattice_point3(8, p);
        sign = JacobianSign::Folds;
      }
    }
  }
  if (sign == JacobianSign::Positive) return;
  char at[160];
  std::snprintf(at, sizeof at, " at reference point (%.3g, %.3g, %.3g)", where.x, where.y, where.z);
  if (sign == JacobianSign::Folds)
    throw Error("the map folds " + mt.name() +
                " (its jacobian determinant is not positive" + at + ")");
  throw Error("the map nearly folds " + mt.name() +
              " (its jacobian determinant comes within about 1e-6 of zero" + at +
              ", or its certification needs more than " + std::to_string(kFoldTetrahedra) + " sub-tetrahedra)");
}

}  // namespace dlmfsi
