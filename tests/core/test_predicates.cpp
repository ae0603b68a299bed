#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/predicates.hpp"

using dlmfsi::orient2d;
using dlmfsi::orient2d_exact;
using dlmfsi::Point;

// Reference: on integer coordinates below 2^26 the determinant is exact in 64-bit integers.
static int orient_int(long long ax, long long ay, long long bx, long long by, long long cx, long long cy) {
  const long long d = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  return (d > 0) - (d < 0);
}

TEST(Predicates, IntegerGridMatchesIntegerArithmetic) {
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<long long> u(-(1LL << 25), 1LL << 25);
  for (int i = 0; i < 200000; ++i) {
    long long c[6];
    for (auto& v : c) v = u(rng);
    if (i % 3 == 0) {  // force collinear triples
      c[4] = c[0] + 2 * (c[2] - c[0]);
      c[5] = c[1] + 2 * (c[3] - c[1]);
    }
    Point a{double(c[0]), double(c[1])}, b{double(c[2]), double(c[3])}, p{double(c[4]), double(c[5])};
    ASSERT_EQ(orient2d(a, b, p), orient_int(c[0], c[1], c[2], c[3], c[4], c[5]));
  }
}

TEST(Predicates, NearlyCollinearPointsOnALine) {
  // Points on the line y = x scaled by a non-representable slope: the floating-point determinant is noise,
  // the exact one is decided by the actual doubles. Shifting by one ulp must flip the sign consistently.
  Point a{0.1, 0.1 * 3.3}, b{1e3 + 0.7, (1e3 + 0.7) * 3.3};
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.001 * i + 0.123;
    Point p{t, t * 3.3};
    const int s = orient2d(a, b, p);
    EXPECT_EQ(s, orient2d_exact(a, b, p));
    Point up{p.x, std::nextafter(p.y, 1e300)}, down{p.x, std::nextafter(p.y, -1e300)};
    // moving p up moves it to the left of a->b (counter-clockwise side)
    EXPECT_GE(orient2d(a, b, up), s);
    EXPECT_LE(orient2d(a, b, down), s);
    EXPECT_TRUE(orient2d(a, b, up) == 1 || orient2d(a, b, down) == -1);
  }
}

TEST(Predicates, ExactIsAntisymmetricAndCyclic) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100000; ++i) {
    Point a{u(rng), u(rng)}, b{u(rng), u(rng)};
    const double t = u(rng);
    Point c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};  // nearly collinear
    const int s = orient2d(a, b, c);
    ASSERT_EQ(s, orient2d(b, c, a));
    ASSERT_EQ(s, orient2d(c, a, b));
    ASSERT_EQ(-s, orient2d(b, a, c));
    ASSERT_EQ(s, orient2d_exact(a, b, c));
  }
}

TEST(Predicates, HugeAndTinyCoordinates) {
  for (double scale : {1e-140, 1e-20, 1.0, 1e20, 1e140}) {
    Point a{0, 0}, b{scale, scale}, c{2 * scale, 2 * scale};
    EXPECT_EQ(orient2d(a, b, c), 0) << scale;
    Point d{2 * scale, std::nextafter(2 * scale, 1e300)};
    EXPECT_EQ(orient2d(a, b, d), 1) << scale;
  }
}
