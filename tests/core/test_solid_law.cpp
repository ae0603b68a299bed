// solid/law: the stresses against closed forms (stretch, shear, rotation), the tangent against central
// differences of P, the right-hand side's stress against DP(Fl)[Fl] - P(Fl), frame invariance of svk and nh.
// solid/law_assembly: sums over a mesh against the same closed forms, symmetry, plus= and the in-place sum.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "errors.hpp"
#include "fe/rules.hpp"
#include "solid/law.hpp"
#include "solid/law_assembly.hpp"
#include "support.hpp"

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

// solid/law_assembly on P1 positions over a grid, the map affine (Fl = F everywhere): paired with a linear
// test field t, r's and K's sums are the area times one entry of a stress (closed forms, independent of the
// code's), K is symmetric, a sum with plus= is K + A, and the in-place sum of a later call is the first's.
namespace {

using dlmfsi::CsrMatrix;
using dlmfsi::test::grid_mesh;

struct GridProblem {
  dlmfsi::Mesh mesh = grid_mesh(3, 2, 0.1, -0.2, 0.9, 0.5);
  dlmfsi::test::VectorP1 position{mesh};
  dlmfsi::test::P1 scalar{mesh};
  const std::vector<dlmfsi::RulePoint>& rule = dlmfsi::triangle_rule(2);
  dlmfsi::RuleGradients pos{position, static_cast<int>(mesh.triangles.size()), {0, 1}, rule};
  dlmfsi::RuleGradients map{scalar, static_cast<int>(mesh.triangles.size()), {0}, rule};
  std::vector<double> xl, yl, areas;
  double area = 0;
  // the affine map x -> F x
  explicit GridProblem(const Gradient2& f) {
    for (const auto& v : mesh.vertices) {
      xl.push_back(f[0] * v.x + f[1] * v.y);
      yl.push_back(f[2] * v.x + f[3] * v.y);
    }
    for (size_t k = 0; k < mesh.triangles.size(); ++k) {
      dlmfsi::Point p[3];
      mesh.corners(static_cast<int>(k), p);
      areas.push_back(cross(p[1] - p[0], p[2] - p[0]) / 2);
      area += areas.back();
    }
  }
  dlmfsi::LawProblem problem(SolidLaw law) const {
    dlmfsi::LawProblem p;
    p.law = law;
    p.constants = kC;
    p.position = &pos;
    p.x = {&map, xl.data()};
    p.y = {&map, yl.data()};
    p.rule = &rule;
    p.areas = &areas;
    return p;
  }
  // the vector P1 field (a x + b y, c x + d y)
  std::vector<double> field(const Gradient2& g) const {
    std::vector<double> v;
    for (const auto& p : mesh.vertices) {
      v.push_back(g[0] * p.x + g[1] * p.y);
      v.push_back(g[2] * p.x + g[3] * p.y);
    }
    return v;
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

std::vector<double> times(const CsrMatrix& k, const std::vector<double>& x) {
  std::vector<double> y(k.rows, 0.0);
  for (int i = 0; i < k.rows; ++i)
    for (int e = k.start[i]; e < k.start[i + 1]; ++e) y[i] += k.value[e] * x[k.column[e]];
  return y;
}

TEST(SolidLawAssembly, StretchedSvkRightHandSide) {
  const double a = 1.3, l = kC.lambda, m = kC.mu;
  GridProblem s({a, 0, 0, 1});
  dlmfsi::LawAssembly assembly;
  std::vector<double> r;
  assembly.rhs(s.problem(SolidLaw::Svk), r);
  // int R : Grad t = area R_ij for t = E_ij x; R = Fl (lambda tr C I + 2 mu C), C = diag(a^2, 1)
  const double r11 = a * (l * (a * a + 1) + 2 * m * a * a), r22 = l * (a * a + 1) + 2 * m;
  EXPECT_NEAR(dot(r, s.field({1, 0, 0, 0})), s.area * r11, 1e-10 * s.area * r11);
  EXPECT_NEAR(dot(r, s.field({0, 0, 0, 1})), s.area * r22, 1e-10 * s.area * r22);
  EXPECT_NEAR(dot(r, s.field({0, 1, 0, 0})), 0, 1e-10 * s.area * r11);
}

TEST(SolidLawAssembly, ListingMatrixOnLinearFields) {
  GridProblem s({1.1, 0.2, -0.1, 0.9});
  dlmfsi::LawAssembly assembly;
  const CsrMatrix& k = assembly.matrix(s.problem(SolidLaw::Listing));
  // t' K u = area DP[H] : G for u = H x, t = G x; listing DP[H] = 2 mu sym H + lambda tr H I
  const Gradient2 h = {0.3, -0.7, 0.4, 1.2}, g = {0.5, 0.25, -1, 2};
  const double sym12 = (h[1] + h[2]) / 2, tr = h[0] + h[3];
  const Gradient2 dp = {2 * kC.mu * h[0] + kC.lambda * tr, 2 * kC.mu * sym12, 2 * kC.mu * sym12,
                        2 * kC.mu * h[3] + kC.lambda * tr};
  const double want = s.area * (dp[0] * g[0] + dp[1] * g[1] + dp[2] * g[2] + dp[3] * g[3]);
  EXPECT_NEAR(dot(s.field(g), times(k, s.field(h))), want, 1e-10 * std::abs(want));
}

TEST(SolidLawAssembly, SymmetricAndSummedWithPlus) {
  GridProblem s({1.2, 0.3, -0.2, 0.8});
  for (SolidLaw law : kLaws) {
    dlmfsi::LawAssembly assembly, fresh;
    const CsrMatrix k = assembly.matrix(s.problem(law));
    for (int i = 0; i < k.rows; ++i)
      for (int e = k.start[i]; e < k.start[i + 1]; ++e)
        EXPECT_NEAR(k.value[e], k.at(k.column[e], i), 1e-9 * (kC.lambda + kC.mu)) << solid_law_name(law);
    // A: a diagonal and one entry off K's pattern
    std::vector<dlmfsi::Triplet> a;
    for (int i = 0; i < k.rows; ++i) a.emplace_back(i, i, 1e30 * (i % 3 == 0));
    a.emplace_back(0, k.rows - 1, 7.0);
    const CsrMatrix sum1 = assembly.matrix(s.problem(law), &a);
    const CsrMatrix sum2 = assembly.matrix(s.problem(law), &a);  // in place on the kept pattern
    const CsrMatrix& reference = fresh.matrix(s.problem(law), &a);
    EXPECT_EQ(sum2.column, reference.column);
    EXPECT_EQ(sum2.value, reference.value);  // bit for bit
    EXPECT_EQ(sum1.value, reference.value);
    EXPECT_EQ(sum2.at(0, k.rows - 1), 7.0 + k.at(0, k.rows - 1));
    EXPECT_EQ(sum2.at(3, 3), 1e30);
    EXPECT_EQ(sum2.at(1, 1), k.at(1, 1));
    const CsrMatrix again = assembly.matrix(s.problem(law));  // without plus: K again
    EXPECT_EQ(again.value, k.value);
  }
}

TEST(SolidLawAssembly, FoldNamesTheTriangle) {
  GridProblem s({-1, 0, 0, 1});
  dlmfsi::LawAssembly assembly;
  try {
    assembly.matrix(s.problem(SolidLaw::NeoHookean));
    ADD_FAILURE() << "no error";
  } catch (const dlmfsi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("solid triangle 0: law nh: J = det F = -1 <= 0"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(assembly.matrix(s.problem(SolidLaw::Svk)));
}

}  // namespace
