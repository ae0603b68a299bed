#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fe/rules.hpp"

using namespace dlmfsi;

static double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

namespace {

// int_T x^a y^b = a! b! / (a + b + 2)! on the reference triangle (area 1/2).
void expect_exact_to_degree(const std::vector<RulePoint>& rule, int d, const char* which) {
  double wsum = 0;
  for (const auto& q : rule) {
    EXPECT_GT(q.weight, 0);
    EXPECT_GE(q.xi.x, 0);
    EXPECT_GE(q.xi.y, 0);
    EXPECT_LE(q.xi.x + q.xi.y, 1 + 1e-15);
    wsum += q.weight;
  }
  EXPECT_NEAR(wsum, 1, 1e-14);
  for (int a = 0; a <= d; ++a)
    for (int b = 0; a + b <= d; ++b) {
      double s = 0;
      for (const auto& q : rule) s += q.weight * std::pow(q.xi.x, a) * std::pow(q.xi.y, b);
      const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
      // positive weights and values: each sum to a few ulps of the exact integral, relatively
      EXPECT_NEAR(0.5 * s, exact, 2e-14 * exact) << which << " degree " << d << " x^" << a << " y^" << b;
    }
}

// A rule of degree d must miss some monomial of degree d + 2 (the test can fail), relatively far above the
// round-off of its sums.
void expect_inexact_beyond(const std::vector<RulePoint>& rule, int d, const char* which) {
  double worst = 0;
  for (int a = 0; a <= d + 2; ++a) {
    const int b = d + 2 - a;
    double s = 0;
    for (const auto& q : rule) s += q.weight * std::pow(q.xi.x, a) * std::pow(q.xi.y, b);
    const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
    worst = std::max(worst, std::fabs(0.5 * s - exact) / exact);
  }
  EXPECT_GT(worst, 1e-8) << which << " degree " << d;
}

}  // namespace

TEST(Rules, ExactForMonomialsUpToTheirDegree) {
  for (int d = 0; d <= 30; ++d) {
    expect_exact_to_degree(triangle_rule(d), d, "triangle_rule");
    expect_exact_to_degree(triangle_rule_for_polynomials(d), d, "triangle_rule_for_polynomials");
  }
}

TEST(Rules, NotExactBeyondTheirDegree) {
  for (int d : {1, 2, 5, 8}) expect_inexact_beyond(triangle_rule(d), d, "triangle_rule");
  for (int d : {10, 12, 14, 16, 18, 20}) expect_inexact_beyond(triangle_rule_for_polynomials(d), d, "for polynomials");
}

// The symmetric rules have fewer points than the products of the same degree.
TEST(Rules, RulesForPolynomialsHaveFewerPoints) {
  const size_t points[] = {25, 33, 42, 55, 67, 79};
  for (int k = 0; k < 6; ++k) {
    const int d = 10 + 2 * k;
    EXPECT_EQ(triangle_rule_for_polynomials(d).size(), points[k]) << d;
    EXPECT_EQ(triangle_rule_for_polynomials(d - 1).size(), points[k]) << d - 1;
    EXPECT_LT(triangle_rule_for_polynomials(d).size(), triangle_rule(d).size()) << d;
  }
}

TEST(Rules, RejectsOutOfRangeDegrees) { EXPECT_THROW(triangle_rule(61), std::runtime_error); }

// int_0^1 x^a = 1 / (a + 1): the line rule of degree d is exact up to x^d; not for (2x - 1)^(2n), n = d / 2 + 1 its
// points (int_0^1 (2x - 1)^(2n) = 1 / (2n + 1), which n Gauss points miss by a relative pi n / 4^n: 1.5e-11 at the
// most points, 21, far above round-off).
TEST(Rules, LineRuleExactUpToItsDegree) {
  for (int d = 0; d <= 40; ++d) {
    const LineRule& rule = line_rule(d);
    ASSERT_EQ(rule.nodes.size(), static_cast<size_t>(d / 2 + 1));
    for (int a = 0; a <= d; ++a) {
      double s = 0;
      for (size_t q = 0; q < rule.nodes.size(); ++q) s += rule.weights[q] * std::pow(rule.nodes[q], a);
      EXPECT_NEAR(s, 1.0 / (a + 1), 1e-14) << "degree " << d << " x^" << a;
    }
    const int beyond = 2 * static_cast<int>(rule.nodes.size());
    double s = 0;
    for (size_t q = 0; q < rule.nodes.size(); ++q) s += rule.weights[q] * std::pow(2 * rule.nodes[q] - 1, beyond);
    EXPECT_GT(std::fabs(s * (beyond + 1) - 1), 1e-13) << "degree " << d;
  }
  EXPECT_THROW(line_rule(41), std::runtime_error);
  EXPECT_THROW(line_rule(-1), std::runtime_error);
}
