#include "map/fold.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "errors.hpp"
#include "fe/lattice.hpp"
#include "fe/matrix_inverse.hpp"

namespace dlmfsi {

namespace {

constexpr int kMaxDegree = 10;

// Row-major inverse of C[p][m] = B_m(lattice point p) for the Bernstein polynomials of degree n,
// B_(a,b) = n! / (a! b! (n-a-b)!) l0^(n-a-b) l1^a l2^b, indexed like the monomials (lattice.hpp):
// Bernstein coefficients = inverse * values at the lattice points.
const std::vector<double>& bernstein_inverse(int n) {
  static const auto table = [] {
    std::vector<std::vector<double>> inv(kMaxDegree + 1);
    for (int deg = 0; deg <= kMaxDegree; ++deg) {
      const int size = monomial_count(deg);
      std::vector<double> b(static_cast<size_t>(size) * size);  // C
      auto factorial = [](int k) {
        double f = 1;
        for (int i = 2; i <= k; ++i) f *= i;
        return f;
      };
      for (int p = 0; p < size; ++p) {
        const Point x = deg == 0 ? Point{1.0 / 3, 1.0 / 3} : lattice_point(deg, p);
        for (int m = 0; m < size; ++m) {
          int ea, eb;
          monomial_exponents(m, ea, eb);
          const int e0 = deg - ea - eb;
          b[p * size + m] = factorial(deg) / (factorial(ea) * factorial(eb) * factorial(e0)) *
                            std::pow(1 - x.x - x.y, e0) * std::pow(x.x, ea) * std::pow(x.y, eb);
        }
      }
      inv[deg] = inverse(b, size);
    }
    return inv;
  }();
  return table[n];
}

}  // namespace

JacobianSign jacobian_sign(const std::function<double(Point)>& det, int n, int max_depth, Point& where) {
  n = std::max(0, std::min(n, kMaxDegree));
  const int size = monomial_count(n);
  const std::vector<double>& inv = bernstein_inverse(n);
  struct Sub {
    Point q[3];
    int depth;
  };
  std::vector<Sub> stack{{{{0, 0}, {1, 0}, {0, 1}}, 0}};
  double values[monomial_count(kMaxDegree)];
  JacobianSign result = JacobianSign::Positive;
  while (!stack.empty()) {
    const Sub s = stack.back();
    stack.pop_back();
    double largest = 0;
    for (int p = 0; p < size; ++p) {
      const Point l = n == 0 ? Point{1.0 / 3, 1.0 / 3} : lattice_point(n, p);
      const Point xi = s.q[0] + l.x * (s.q[1] - s.q[0]) + l.y * (s.q[2] - s.q[0]);
      values[p] = det(xi);
      if (!(values[p] > 0)) {
        where = xi;
        return JacobianSign::Folds;
      }
      largest = std::max(largest, values[p]);
    }
    double smallest = 1e300;
    for (int m = 0; m < size; ++m) {
      double c = 0;
      for (int p = 0; p < size; ++p) c += inv[m * size + p] * values[p];
      smallest = std::min(smallest, c);
    }
    if (smallest > 1e-12 * largest) continue;
    if (s.depth >= max_depth) {
      if (result == JacobianSign::Positive) where = (1.0 / 3) * (s.q[0] + s.q[1] + s.q[2]);
      result = JacobianSign::NearlyFolds;  // keep looking for a certain fold elsewhere
      continue;
    }
    const Point m01 = 0.5 * (s.q[0] + s.q[1]), m12 = 0.5 * (s.q[1] + s.q[2]), m20 = 0.5 * (s.q[2] + s.q[0]);
    stack.push_back({{s.q[0], m01, m20}, s.depth + 1});
    stack.push_back({{m01, s.q[1], m12}, s.depth + 1});
    stack.push_back({{m20, m12, s.q[2]}, s.depth + 1});
    stack.push_back({{m12, m20, m01}, s.depth + 1});
  }
  return result;
}

// With A = [X(1,0) - X(0,0), X(0,1) - X(0,0)] (det A > 0) and E(xi) = A^-1 dX/dxi(xi) - I: every monomial
// lies in [0, 1] on the triangle, so ||E(xi)|| (rows' absolute sums) is at most the rows' sums of the
// absolute coefficients of E. Where that bound is at most 1/2, the eigenvalues of I + E lie within 1/2 of 1
// (real, or a conjugate pair), so det dX/dxi = det A det(I + E) >= det A / 4.
bool jacobian_certainly_positive(const TriangleMap& map) {
  if (!map.fitted()) return false;
  const Point x0 = map.corner_image(0), f1 = map.corner_image(1) - x0, f2 = map.corner_image(2) - x0;
  const double det = cross(f1, f2);
  if (!(det > 0)) return false;
  const double a[2][2] = {{f2.y / det, -f2.x / det}, {-f1.y / det, f1.x / det}};  // A^-1
  const PolynomialMapCoefficients& c = map.coefficients();
  const int terms = monomial_count(map.degree() - 1);
  double row[2] = {0, 0};
  for (int m = 0; m < terms; ++m)
    for (int i = 0; i < 2; ++i) {
      const double e1 = a[i][0] * c.d1[2 * m] + a[i][1] * c.d1[2 * m + 1] - (m == 0 && i == 0 ? 1 : 0);
      const double e2 = a[i][0] * c.d2[2 * m] + a[i][1] * c.d2[2 * m + 1] - (m == 0 && i == 1 ? 1 : 0);
      row[i] += std::fabs(e1) + std::fabs(e2);
    }
  return std::max(row[0], row[1]) <= 0.5;  // false for NaN
}

void check_fold(const TriangleMap& map) {
  if (jacobian_certainly_positive(map)) return;
  auto det = [&map](Point xi) {
    Point x, d1, d2;
    map.reference_derivatives(xi, x, d1, d2);
    return cross(d1, d2);  // det dX/dxi = det dX/ds det ds/dxi: the sign of det dX/ds (s counter-clockwise)
  };
  Point where;
  JacobianSign sign;
  if (map.fitted()) {
    sign = jacobian_sign(det, 2 * (map.degree() - 1), 10, where);
  } else {
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
    throw Error("the map folds " + map.name() + " (its jacobian determinant is not positive" + at + ")");
  throw Error("the map nearly folds " + map.name() + " (its jacobian determinant comes within about 1e-6 of zero" +
              at + ")");
}

}  // namespace dlmfsi
