// solid/law: the stresses against closed forms (stretch, shear, rotation), the tangent against central
// differences of P, the right-hand side's stress against DP(Fl)[Fl] - P(Fl), frame invariance of svk and nh.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "errors.hpp"
#include "solid/law.hpp"

namespace {

using dlmfsi::Gradient2;
using dlmfsi::LawConstants;
using dlmfsi::SolidLaw;

const LawConstants kC{8e3, 2e3};  // lambda, mu
const SolidLaw kLaws[] = {SolidLaw::Listing, SolidLaw::Svk, SolidLaw::NeoHookean};

Gradient2 product(const Gradient2& a, const Gradient2& b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3]};
}
Gradient2 rotation(double theta) { return {std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta)}; }

void expect_near(const Gradient2& got, const Gradient2& want, double tol, const char* what) {
  for (int e = 0; e < 4; ++e) EXPECT_NEAR(got[e], want[e], tol) << what << " entry " << e;
}

// Gradients with J > 0, away from the identity.
std::vector<Gradient2> samples() {
  return {{1, 0, 0, 1}, {1.3, 0.2, -0.1, 0.8}, {0.7, -0.4, 0.3, 1.2}, {2.1, 0.5, 0.4, 0.6}, {0.95, 0.05, 0.02, 1.01}};
}

TEST(SolidLaw, StretchClosedForms) {
  const double a = 1.3, l = kC.lambda, m = kC.mu;
  const Gradient2 f = {a, 0, 0, 1};
  expect_near(first_piola(SolidLaw::Svk, kC, f), {a * (l + 2 * m) * (a * a - 1) / 2, 0, 0, l * (a * a - 1) / 2}, 1e-9, "svk");
  expect_near(first_piola(SolidLaw::NeoHookean, kC, f), {m * (a - 1 / a) + l * std::log(a) / a, 0, 0, l * std::log(a)}, 1e-9, "nh");
  expect_near(first_piola(SolidLaw::Listing, kC, f), {(l + 2 * m) * (a - 1), 0, 0, l * (a - 1)}, 1e-9, "listing");
  // DP(Fl)[Fl] - P(Fl): svk Fl (lambda tr C I + 2 mu C), C = diag(a^2, 1); nh 2 (mu + lambda - lambda ln a) Fl^-T
  expect_near(linearization_stress(SolidLaw::Svk, kC, f),
              {a * (l * (a * a + 1) + 2 * m * a * a), 0, 0, l * (a * a + 1) + 2 * m}, 1e-9, "svk rhs");
  const double n = 2 * (m + l - l * std::log(a));
  expect_near(linearization_stress(SolidLaw::NeoHookean, kC, f), {n / a, 0, 0, n}, 1e-9, "nh rhs");
  expect_near(linearization_stress(SolidLaw::Listing, kC, f), {2 * (m + l), 0, 0, 2 * (m + l)}, 1e-9, "listing rhs");
}

TEST(SolidLaw, ShearClosedForms) {
  const double g = 0.3, l = kC.lambda, m = kC.mu, s = (l / 2 + m) * g * g;
  const Gradient2 f = {1, g, 0, 1};
  expect_near(first_piola(SolidLaw::Svk, kC, f), {s, m * g + g * s, m * g, s}, 1e-9, "svk");
  expect_near(first_piola(SolidLaw::NeoHookean, kC, f), {0, m * g, m * g, 0}, 1e-9, "nh");
  expect_near(first_piola(SolidLaw::Listing, kC, f), {0, m * g, m * g, 0}, 1e-9, "listing");
}

TEST(SolidLaw, RotationClosedForms) {
  const double theta = 0.7, l = kC.lambda, m = kC.mu;
  const Gradient2 r = rotation(theta);
  expect_near(first_piola(SolidLaw::Svk, kC, r), {0, 0, 0, 0}, 1e-10, "svk");
  expect_near(first_piola(SolidLaw::NeoHookean, kC, r), {0, 0, 0, 0}, 1e-10, "nh");
  const double d = 2 * (m + l) * (std::cos(theta) - 1);
  expect_near(first_piola(SolidLaw::Listing, kC, r), {d, 0, 0, d}, 1e-9, "listing");
  // C = I: svk 2 (lambda + mu) R; J = 1, K = R: nh 2 (mu + lambda) R
  const Gradient2 twice = {2 * (l + m) * r[0], 2 * (l + m) * r[1], 2 * (l + m) * r[2], 2 * (l + m) * r[3]};
  expect_near(linearization_stress(SolidLaw::Svk, kC, r), twice, 1e-9, "svk rhs");
  expect_near(linearization_stress(SolidLaw::NeoHookean, kC, r), twice, 1e-9, "nh rhs");
}

// t[4 i + j] = d P_i / d F_j, against central differences of P (step 1e-5: error ~ 1e-10 |P'''|).
TEST(SolidLaw, TangentIsTheDerivativeOfP) {
  const double h = 1e-5;
  for (SolidLaw law : kLaws)
    for (const Gradient2& f : samples()) {
      double t[16];
      tangent(law, kC, f, t);
      for (int j = 0; j < 4; ++j) {
        Gradient2 plus = f, minus = f;
        plus[j] += h;
        minus[j] -= h;
        const Gradient2 pp = first_piola(law, kC, plus), pm = first_piola(law, kC, minus);
        for (int i = 0; i < 4; ++i)
          EXPECT_NEAR(t[4 * i + j], (pp[i] - pm[i]) / (2 * h), 1e-5 * (kC.lambda + kC.mu))
              << solid_law_name(law) << " t[" << i << "][" << j << "]";
      }
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < i; ++j) EXPECT_NEAR(t[4 * i + j], t[4 * j + i], 1e-9 * (kC.lambda + kC.mu)) << "symmetric";
    }
}

// linearization_stress's closed forms are DP(Fl)[Fl] - P(Fl).
TEST(SolidLaw, RightHandSideStressIsTheLinearizationsConstant) {
  for (SolidLaw law : kLaws)
    for (const Gradient2& f : samples()) {
      const Gradient2 dp = stress_derivative(law, kC, f, f), p = first_piola(law, kC, f);
      expect_near(linearization_stress(law, kC, f), {dp[0] - p[0], dp[1] - p[1], dp[2] - p[2], dp[3] - p[3]},
                  1e-9 * (kC.lambda + kC.mu), solid_law_name(law));
    }
}

// P(Q F) = Q P(F), DP(Q F)[Q H] = Q DP(F)[H] and the right-hand side's stress likewise, Q a rotation.
TEST(SolidLaw, SvkAndNeoHookeanAreFrameInvariant) {
  const Gradient2 q = rotation(-1.1), h = {0.3, -0.2, 0.5, 0.1};
  for (SolidLaw law : {SolidLaw::Svk, SolidLaw::NeoHookean})
    for (const Gradient2& f : samples()) {
      const double tol = 1e-10 * (kC.lambda + kC.mu);
      expect_near(first_piola(law, kC, product(q, f)), product(q, first_piola(law, kC, f)), tol, "P");
      expect_near(stress_derivative(law, kC, product(q, f), product(q, h)),
                  product(q, stress_derivative(law, kC, f, h)), tol, "DP");
      expect_near(linearization_stress(law, kC, product(q, f)), product(q, linearization_stress(law, kC, f)), tol,
                  "rhs");
    }
  // the listing is not: a rotation of the identity stresses it
  const Gradient2 p = first_piola(SolidLaw::Listing, kC, q);
  EXPECT_GT(std::abs(p[0]), 1e3);
}

TEST(SolidLaw, BadInputIsNamed) {
  EXPECT_THROW(dlmfsi::solid_law("linear"), dlmfsi::Error);
  EXPECT_EQ(dlmfsi::solid_law("nh"), SolidLaw::NeoHookean);
  double t[16];
  const Gradient2 fold = {-1, 0, 0, 1}, flat = {1, 2, 0.5, 1};
  for (const Gradient2& f : {fold, flat}) {
    EXPECT_THROW(tangent(SolidLaw::NeoHookean, kC, f, t), dlmfsi::Error);
    EXPECT_THROW(linearization_stress(SolidLaw::NeoHookean, kC, f), dlmfsi::Error);
    EXPECT_THROW(first_piola(SolidLaw::NeoHookean, kC, f), dlmfsi::Error);
    EXPECT_NO_THROW(tangent(SolidLaw::Svk, kC, f, t));
  }
  try {
    linearization_stress(SolidLaw::NeoHookean, kC, fold);
  } catch (const dlmfsi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("J = det F = -1 <= 0"), std::string::npos) << e.what();
  }
}

}  // namespace
