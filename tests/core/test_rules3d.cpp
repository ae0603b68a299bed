// Tetrahedron rules: exact on every monomial up to their degree, not beyond; Gauss-Jacobi rules exact on
// their weight's moments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fe/rules.hpp"

using namespace dlmfsi;

namespace {
double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }
// int_T x^a y^b z^c = a! b! c! / (a + b + c + 3)! on the reference tetrahedron (volume 1/6).
double monomial_integral(int a, int b, int c) { return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3); }
}  // namespace

TEST(Rules3d, GaussJacobiIntegratesItsWeightsMoments) {
  // int_0^1 (1 - u)^alpha u^k du = alpha! k! / (alpha + k + 1)!
  double worst = 0;
  for (int alpha = 0; alpha <= 2; ++alpha)
    for (int n = 1; n <= 20; ++n) {
      std::vector<double> x, w;
      gauss_jacobi(n, alpha, x, w);
      for (int k = 0; k <= 2 * n - 1; ++k) {
        double s = 0;
        for (int i = 0; i < n; ++i) s += w[i] * std::pow(x[i], k);
        const double exact = factorial(alpha) * factorial(k) / factorial(alpha + k + 1);
        worst = std::max(worst, std::fabs(s - exact) / exact);  // positive weights: no cancellation
      }
    }
  EXPECT_LE(worst, 1e-13);
}

namespace {

void expect_exact_to_degree(const std::vector<RulePoint3>& rule, int d, const char* which) {
  double wsum = 0;
  for (const auto& q : rule) {
    EXPECT_GT(q.weight, 0);
    EXPECT_GE(std::min({q.xi.x, q.xi.y, q.xi.z}), 0);
    EXPECT_LE(q.xi.x + q.xi.y + q.xi.z, 1 + 1e-15);
    wsum += q.weight;
  }
  EXPECT_NEAR(wsum, 1, 1e-14);
  double worst = 0;
  for (int a = 0; a <= d; ++a)
    for (int b = 0; a + b <= d; ++b)
      for (int c = 0; a + b + c <= d; ++c) {
        double s = 0;
        for (const auto& q : rule) s += q.weight * std::pow(q.xi.x, a) * std::pow(q.xi.y, b) * std::pow(q.xi.z, c);
        const double exact = monomial_integral(a, b, c);
        worst = std::max(worst, std::fabs(s / 6 - exact) / exact);  // monomials are >= 0 on T: no cancellation
      }
  EXPECT_LE(worst, 1e-13) << which << " degree " << d;
}

// A rule of degree d must miss some monomial of degree d + 2 (the test can fail).
void expect_inexact_beyond(const std::vector<RulePoint3>& rule, int d, const char* which) {
  double worst = 0;
  for (int a = 0; a <= d + 2; ++a)
    for (int b = 0; a + b <= d + 2; ++b) {
      const int c = d + 2 - a - b;
      double s = 0;
      for (const auto& q : rule) s += q.weight * std::pow(q.xi.x, a) * std::pow(q.xi.y, b) * std::pow(q.xi.z, c);
      worst = std::max(worst, std::fabs(s / 6 - monomial_integral(a, b, c)) / monomial_integral(a, b, c));
    }
  EXPECT_GT(worst, 1e-6) << which << " degree " << d;
}

}  // namespace

TEST(Rules3d, ExactForMonomialsUpToTheirDegree) {
  for (int d = 0; d <= 18; ++d) {
    expect_exact_to_degree(tetrahedron_rule(d), d, "tetrahedron_rule");
    expect_exact_to_degree(tetrahedron_rule_for_polynomials(d), d, "tetrahedron_rule_for_polynomials");
  }
}

TEST(Rules3d, NotExactBeyondTheirDegree) {
  for (int d : {1, 2, 3, 5, 6, 7, 8, 9}) expect_inexact_beyond(tetrahedron_rule(d), d, "tetrahedron_rule");
  for (int d = 10; d <= 17; ++d) expect_inexact_beyond(tetrahedron_rule_for_polynomials(d), d, "for polynomials");
}

// The symmetric rules have fewer points than the products of the same degree.
TEST(Rules3d, RulesForPolynomialsHaveFewerPoints) {
  const size_t points[] = {95, 119, 147, 171, 229, 265, 341, 381};
  for (int d = 10; d <= 17; ++d) {
    EXPECT_EQ(tetrahedron_rule_for_polynomials(d).size(), points[d - 10]) << d;
    EXPECT_LT(tetrahedron_rule_for_polynomials(d).size(), tetrahedron_rule(d).size()) << d;
  }
}

TEST(Rules3d, RejectsOutOfRangeDegrees) { EXPECT_THROW(tetrahedron_rule(41), std::runtime_error); }
