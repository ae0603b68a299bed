#include <gtest/gtest.h>

#include <cmath>

#include "fe/rules.hpp"

using namespace dlmfsi;

static double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// int_T x^a y^b = a! b! / (a + b + 2)! on the reference triangle (area 1/2).
TEST(Rules, ExactForMonomialsUpToTheirDegree) {
  for (int d = 0; d <= 30; ++d) {
    const auto& rule = triangle_rule(d);
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
        EXPECT_NEAR(0.5 * s, exact, 2e-14 * exact) << "degree " << d << " x^" << a << " y^" << b;
      }
  }
}

TEST(Rules, NotExactBeyondTheirDegree) {
  // A rule of degree d must miss some monomial of degree d + 2 (the test can fail).
  for (int d : {1, 2, 5, 8, 10, 12, 14, 16, 18, 20}) {
    const auto& rule = triangle_rule(d);
    double worst = 0;
    for (int a = 0; a <= d + 2; ++a) {
      const int b = d + 2 - a;
      double s = 0;
      for (const auto& q : rule) s += q.weight * std::pow(q.xi.x, a) * std::pow(q.xi.y, b);
      const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
      worst = std::max(worst, std::fabs(0.5 * s - exact) / exact);
    }
    EXPECT_GT(worst, 1e-8) << d;  // relative: far above the round-off of the sums
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
