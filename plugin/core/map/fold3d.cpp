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

}  // namespace dlmfsi
