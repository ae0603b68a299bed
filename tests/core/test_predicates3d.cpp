// orient3d against integer arithmetic and GMP rationals, on random, near-coplanar and degenerate points,
// at scales from subnormals to 1e300.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/predicates3d.hpp"
#include "reference3d.hpp"

using dlmfsi::orient3d;
using dlmfsi::orient3d_exact;
using dlmfsi::orient3d_filter;
using dlmfsi::orient3d_value;
using dlmfsi::ScaledValue;
using dlmfsi::Point3;
using dlmfsi::ref::exact_orientation3d;
using dlmfsi::ref::exact_orientation3d_value;

namespace {

Point3 scaled(Point3 p, int e) { return {std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e)}; }

// A point near the plane of a, b, c: a + s (b - a) + t (c - a) rounded, so exactly on it or within an ulp.
Point3 near_plane(Point3 a, Point3 b, Point3 c, double s, double t) {
  return {a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
          a.z + s * (b.z - a.z) + t * (c.z - a.z)};
}

}  // namespace

TEST(Predicates3d, IntegerGridMatchesIntegerArithmetic) {
  // Coordinates below 2^16: the determinant of the differences is exact in 64-bit integers.
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<long long> u(-(1LL << 16), 1LL << 16), small(-3, 3);
  long zeros = 0;
  for (int i = 0; i < 200000; ++i) {
    long long c[12];
    for (auto& v : c) v = u(rng);
    if (i % 3 == 0) {  // d on the plane of a, b, c (integer combination)
      const long long s = small(rng), t = small(rng);
      for (int k = 0; k < 3; ++k) c[9 + k] = c[k] + s * (c[3 + k] - c[k]) + t * (c[6 + k] - c[k]);
    }
    const long long ux = c[3] - c[0], uy = c[4] - c[1], uz = c[5] - c[2];
    const long long vx = c[6] - c[0], vy = c[7] - c[1], vz = c[8] - c[2];
    const long long wx = c[9] - c[0], wy = c[10] - c[1], wz = c[11] - c[2];
    const long long d = ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
    const Point3 a{double(c[0]), double(c[1]), double(c[2])}, b{double(c[3]), double(c[4]), double(c[5])};
    const Point3 p{double(c[6]), double(c[7]), double(c[8])}, q{double(c[9]), double(c[10]), double(c[11])};
    ASSERT_EQ(orient3d(a, b, p, q), (d > 0) - (d < 0));
    ASSERT_EQ(orient3d_exact(a, b, p, q), (d > 0) - (d < 0));
    zeros += d == 0;
  }
  EXPECT_GT(zeros, 60000);
}

TEST(Predicates3d, NearlyCoplanarMatchesRationals) {
  // d on the plane of a, b, c up to one rounding: the filter cannot decide, the exact path must.
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  long undecided = 0, positive = 0, negative = 0;
  for (int i = 0; i < 100000; ++i) {
    Point3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    if (i % 4 == 1) {  // far from the origin: the differences are not exact
      const Point3 o{1e3 * u(rng), 1e3 * u(rng), 1e3 * u(rng)};
      a = a + o;
      b = b + o;
      c = c + o;
    }
    const Point3 d = near_plane(a, b, c, u(rng), u(rng));
    const int s = exact_orientation3d(a, b, c, d);
    ASSERT_EQ(orient3d(a, b, c, d), s) << i;
    undecided += orient3d_filter(a, b, c, d) == 0;
    positive += s > 0;
    negative += s < 0;
  }
  EXPECT_GT(undecided, 50000);  // the exact path was exercised
  EXPECT_GT(positive, 10000);  // rounding puts d on either side
  EXPECT_GT(negative, 10000);
}

TEST(Predicates3d, OneUlpOffAPlaneHasTheSignOfTheStep) {
  // Points exactly on the plane z = 0.1 x + 0.3 y (dyadic rationals make it exact), moved by one ulp in z.
  const Point3 a{0, 0, 0}, b{1, 0, 0.125}, c{0, 1, 0.375};
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> k(-1024, 1024);
  for (int i = 0; i < 20000; ++i) {
    const double x = k(rng) / 64.0, y = k(rng) / 64.0;
    const Point3 on{x, y, 0.125 * x + 0.375 * y};
    ASSERT_EQ(orient3d(a, b, c, on), 0);
    const Point3 up{on.x, on.y, std::nextafter(on.z, 1e300)}, down{on.x, on.y, std::nextafter(on.z, -1e300)};
    // (b - a) x (c - a) = (-0.125, -0.375, 1): up is on its side
    ASSERT_EQ(orient3d(a, b, c, up), 1);
    ASSERT_EQ(orient3d(a, b, c, down), -1);
  }
}

TEST(Predicates3d, PermutationsChangeTheSignByTheirParity) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    const Point3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Point3 d = i % 2 ? near_plane(a, b, c, u(rng), u(rng)) : Point3{u(rng), u(rng), u(rng)};
    const int s = orient3d(a, b, c, d);
    ASSERT_EQ(orient3d(b, c, a, d), s);
    ASSERT_EQ(orient3d(b, a, d, c), s);
    ASSERT_EQ(orient3d(d, c, b, a), s);   // two swaps
    ASSERT_EQ(orient3d(b, a, c, d), -s);  // one swap
    ASSERT_EQ(orient3d(a, b, d, c), -s);
    ASSERT_EQ(orient3d(d, b, c, a), -s);
  }
}

TEST(Predicates3d, DegenerateConfigurationsAreExactlyZero) {
  const Point3 a{0.1, 0.2, 0.3}, b{1.7, -0.4, 2.9}, c{-3.3, 0.55, 1.1};
  EXPECT_EQ(orient3d(a, a, b, c), 0);  // coincident points
  EXPECT_EQ(orient3d(a, b, c, c), 0);
  EXPECT_EQ(orient3d(a, b, a, b), 0);
  const Point3 p{0.5, 0.25, 0.125}, q{1.5, -0.75, 2.25};
  EXPECT_EQ(orient3d(p, q, 0.5 * (p + q), c), 0);  // three collinear (an exact midpoint)
  EXPECT_EQ(orient3d(p, c, q, 0.25 * p + 0.75 * q), 0);
  EXPECT_EQ(orient3d(a, b, c, a + b - c), exact_orientation3d(a, b, c, a + b - c));
  // the plane z = 0 at any scale
  for (double s : {1e-300, 1e-100, 1.0, 1e100, 1e300}) {
    const Point3 p{0.3 * s, 0.7 * s, 0}, q{-0.9 * s, 0.1 * s, 0}, r{0.2 * s, -0.5 * s, 0}, o{0.11 * s, 0.13 * s, 0};
    EXPECT_EQ(orient3d(p, q, r, o), 0) << s;
  }
  EXPECT_EQ(orient3d(Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0, 0, 1}), 1);  // FreeFEM's reference tet
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(orient3d(a, b, c, Point3{inf, 0, 0}), 0);  // outside the contract: 0, nothing undefined
  EXPECT_EQ(orient3d(a, b, c, Point3{0, nan, 0}), 0);
}

TEST(Predicates3d, AnyScaleFromSubnormalsToHuge) {
  // Near-coplanar configurations scaled by powers of two (which keep the sign while nothing underflows),
  // and configurations whose coordinates mix scales, against GMP rationals.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> scale(-1000, 1000), mixed(-340, 340);
  long integer_path = 0;
  for (int i = 0; i < 20000; ++i) {
    const Point3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Point3 d = i % 2 ? near_plane(a, b, c, u(rng), u(rng)) : Point3{u(rng), u(rng), u(rng)};
    const int s = exact_orientation3d(a, b, c, d);
    // powers of two down to 2^-700 keep every coordinate normal: the sign cannot change
    const int e = std::max(-700, scale(rng));
    ASSERT_EQ(orient3d(scaled(a, e), scaled(b, e), scaled(c, e), scaled(d, e)), s) << e;
    integer_path += std::abs(e) > 300;
    // the same points moved to 1e-100 and 1e100 scales within one call, and subnormal coordinates
    Point3 p[4] = {a, b, c, d};
    for (Point3& x : p) {
      x = {std::ldexp(x.x, mixed(rng)), std::ldexp(x.y, mixed(rng)), std::ldexp(x.z, mixed(rng))};
      if (rng() % 8 == 0) x.z = std::ldexp(u(rng), -1030 - static_cast<int>(rng() % 40));  // subnormal
    }
    ASSERT_EQ(orient3d(p[0], p[1], p[2], p[3]), exact_orientation3d(p[0], p[1], p[2], p[3])) << i;
  }
  EXPECT_GT(integer_path, 5000);
}

TEST(Predicates3d, ValuesBelowTheDoublesKeepTheirDigits) {
  // orient3d_value (the constructions' determinant) against GMP rationals to a few ulps, also where the
  // determinant lies far below the doubles: points one and two subnormal steps apart, differences of
  // 2^-1074 against differences of 1, configurations mixing 1e-100 and 1e100 with subnormal coordinates.
  // (A value rounded to a double first would keep a few bits of these, or none.)
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> mixed(-340, 340);
  const double tiny = std::ldexp(1.0, -1074);
  int below = 0;  // determinants below the smallest normal double
  for (int i = 0; i < 20000; ++i) {
    Point3 p[4];
    for (Point3& x : p) x = {u(rng), u(rng), u(rng)};
    switch (i % 4) {
      case 0:  // four points off the plane z = 0 by 0 to 3 subnormal steps
        for (Point3& x : p) x.z = std::ldexp(static_cast<double>(rng() % 4), -1074);
        break;
      case 1:  // two points one subnormal step apart
        p[0] = {p[1].x, p[1].y, 2 * tiny};
        p[1].z = tiny;
        break;
      case 2:  // mixed scales with subnormal coordinates
        for (Point3& x : p) {
          x = {std::ldexp(x.x, mixed(rng)), std::ldexp(x.y, mixed(rng)), std::ldexp(x.z, mixed(rng))};
          if (rng() % 4 == 0) x.z = std::ldexp(u(rng), -1030 - static_cast<int>(rng() % 40));
        }
        break;
      default:  // near-coplanar at unit scale
        p[3] = near_plane(p[0], p[1], p[2], u(rng), u(rng));
    }
    int e_exact;
    const double m_exact = exact_orientation3d_value(p[0], p[1], p[2], p[3], e_exact);
    const ScaledValue v = orient3d_value(p[0], p[1], p[2], p[3]);
    if (m_exact == 0) {
      ASSERT_EQ(v.m, 0.0) << i;
      continue;
    }
    below += e_exact < -1021;
    ASSERT_TRUE(std::fabs(v.m) >= 0.5 && std::fabs(v.m) < 1) << i;
    // the same value: m 2^e against m' 2^e', compared in the units of the exact one
    const double got = std::ldexp(v.m, v.e - e_exact);
    ASSERT_NEAR(got, m_exact, 8 * 0x1p-53) << i << ": exponent " << e_exact;
  }
  EXPECT_GT(below, 7500);
}
