// roots_in: the crossings of a curved image's edge with a line, as sign changes of a polynomial in [lo, hi].
#include <gtest/gtest.h>

#include "geometry/polynomial_roots.hpp"

namespace dlmfsi {
namespace {

int roots(const double* c, int degree, double* r) {
  return roots_in(c, degree, 0, 1, polynomial_value(c, degree, 0), polynomial_value(c, degree, 1), r);
}

TEST(PolynomialRoots, CubicWithThreeRootsInside) {
  // (t - 0.2)(t - 0.5)(t - 0.9) = t^3 - 1.6 t^2 + 0.73 t - 0.09
  const double c[] = {-0.09, 0.73, -1.6, 1};
  double r[3];
  ASSERT_EQ(roots(c, 3, r), 3);
  EXPECT_NEAR(r[0], 0.2, 1e-15);
  EXPECT_NEAR(r[1], 0.5, 1e-15);
  EXPECT_NEAR(r[2], 0.9, 1e-15);
}

TEST(PolynomialRoots, RootsOutsideAreLeftOut) {
  // (t + 0.5)(t - 0.25)(t - 1.5) = t^3 - 1.25 t^2 - 0.5 t + 0.1875
  const double c[] = {0.1875, -0.5, -1.25, 1};
  double r[3];
  ASSERT_EQ(roots(c, 3, r), 1);
  EXPECT_NEAR(r[0], 0.25, 1e-15);
}

TEST(PolynomialRoots, TangencyIsNoCrossing) {
  // (t - 0.5)^2: the line touches the curve
  const double c[] = {0.25, -1, 1};
  double r[2];
  EXPECT_EQ(roots(c, 2, r), 0);
  // (t - 0.5)^2 (t - 0.75): one crossing, the tangency left out
  const double d[] = {-0.1875, 1, -1.75, 1};
  double s[3];
  ASSERT_EQ(roots(d, 3, s), 1);
  EXPECT_NEAR(s[0], 0.75, 1e-15);
}

TEST(PolynomialRoots, ZerosAtTheEndsCount) {
  // t (t - 1): the curve crosses the line at both ends of the edge (image corners on the line)
  const double c[] = {0, -1, 1};
  double r[2];
  ASSERT_EQ(roots(c, 2, r), 2);
  EXPECT_EQ(r[0], 0);
  EXPECT_EQ(r[1], 1);
}

TEST(PolynomialRoots, ZeroPolynomialHasNone) {
  const double c[] = {0, 0, 0};
  double r[2];
  EXPECT_EQ(roots(c, 2, r), 0);
}

TEST(PolynomialRoots, EndValuesGivenByTheCallerDecide) {
  // p(1) is 1e-17 by Horner's rule, but the caller knows the end (an image corner shared by two edges) as
  // -1e-17: the sign change inside is found, as the neighbouring edge sees it.
  const double c[] = {0.5, -0.5 + 1e-17};
  double r[1];
  EXPECT_EQ(roots_in(c, 1, 0, 1, 0.5, -1e-17, r), 1);
  EXPECT_EQ(roots_in(c, 1, 0, 1, 0.5, 1e-17, r), 0);
}

TEST(PolynomialRoots, CloseRootsAreSeparated) {
  // (t - 0.5)(t - 0.5 - 1e-9): two crossings, in order, on either side of the critical point; each known to
  // about eps / |p'| = 1e-16 / 1e-9 (the values' round-off against the slope between such close roots).
  const double a = 0.5, b = 0.5 + 1e-9;
  const double c[] = {a * b, -(a + b), 1};
  double r[2];
  ASSERT_EQ(roots(c, 2, r), 2);
  EXPECT_LT(r[0], 0.5 * (a + b));
  EXPECT_GT(r[1], 0.5 * (a + b));
  EXPECT_NEAR(r[0], a, 2e-8);
  EXPECT_NEAR(r[1], b, 2e-8);
}

}  // namespace
}  // namespace dlmfsi
