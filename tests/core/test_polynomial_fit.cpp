// Bases as polynomials: the lattice fit's zeros (polynomial_fit.hpp: a basis fitted at a degree above its
// own gets exact zeros for the monomials it does not have, and still evaluates the basis), in 2D and 3D;
// and the 3D bases' inner loop (points_evaluation3d.hpp): polynomials of every lattice degree, sparse and
// dense, with twins, evaluated with their physical gradients, against sums of c x^a y^b z^c written from
// the exponents in long double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "fe/basis_fit.hpp"
#include "fe/lattice3d.hpp"
#include "fe/polynomial_basis.hpp"
#include "fe/polynomial_basis3d.hpp"
#include "fe/points_evaluation3d.hpp"
#include "support.hpp"
#include "support3d.hpp"

using namespace dlmfsi;

namespace {

long double power(long double x, int e) { return e == 0 ? 1.0L : std::pow(x, e); }

// Value and reference derivatives of sum_m c[m] xi^(exponents of m), term by term.
void reference_sums(int degree, const double* c, Point3 xi, long double out[4]) {
  std::fill(out, out + 4, 0.0L);
  for (int m = 0; m < monomial_count3(degree); ++m) {
    int e[3];
    monomial_exponents3(m, e[0], e[1], e[2]);
    const long double x[3] = {xi.x, xi.y, xi.z};
    out[0] += c[m] * power(x[0], e[0]) * power(x[1], e[1]) * power(x[2], e[2]);
    for (int i = 0; i < 3; ++i) {
      if (e[i] == 0) continue;
      int f[3] = {e[0], e[1], e[2]};
      --f[i];
      out[1 + i] += c[m] * e[i] * power(x[0], f[0]) * power(x[1], f[1]) * power(x[2], f[2]);
    }
  }
}

// width = 5 polynomials of the degree: 0, 1, 2 with none, half and most of their coefficients zero, 3 a
// twin of 1 (twin[3] = 1), 4 all zero.
constexpr int kWidth = 5;
constexpr int kTwin[kWidth] = {-1, -1, -1, 1, -1};
std::vector<double> sparse_and_dense(int degree, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1, 1), pick(0, 1);
  const int nm = monomial_count3(degree);
  std::vector<double> c(static_cast<size_t>(kWidth) * nm, 0.0);
  const double keep[3] = {1.0, 0.5, 0.15};
  for (int f = 0; f < 3; ++f)
    for (int m = 0; m < nm; ++m)
      if (pick(gen) < keep[f]) c[f * nm + m] = u(gen);
  std::copy(&c[nm], &c[2 * nm], &c[3 * nm]);
  return c;
}

}  // namespace

TEST(PolynomialValues3d, SparseAndDensePolynomialsOfEveryDegreeWithTheirGradients) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> pick(0, 1);
  double worst = 0;
  for (int degree = 0; degree <= kMaxLatticeDegree; ++degree) {
    const int nm = monomial_count3(degree), width = kWidth, n = 13;
    const std::vector<double> c = sparse_and_dense(degree, gen);
    const int* twin = kTwin;
    const double j[9] = {1.5, 0.2, -0.3, 0.1, -2.0, 0.4, 0.7, 0.3, 0.9};  // d xi / d x, row-major
    std::vector<Point3> xi(n);
    for (auto& p : xi) p = {pick(gen), pick(gen), pick(gen)};
    for (bool with_twins : {false, true}) {
      std::vector<double> value(static_cast<size_t>(width) * n), gradient(3 * value.size());
      PolynomialTerms3 terms(degree, c.data(), width);
      terms.evaluate(with_twins ? twin : nullptr, j, xi.data(), n, value.data(), gradient.data());
      std::vector<double> once(value.size()), once_gradient(gradient.size());
      evaluate_polynomials3(degree, c.data(), width, with_twins ? twin : nullptr, j, xi.data(), n, once.data(),
                            once_gradient.data());
      EXPECT_EQ(value, once);
      EXPECT_EQ(gradient, once_gradient);
      for (int f = 0; f < width; ++f)
        for (int p = 0; p < n; ++p) {
          long double r[4];
          reference_sums(degree, &c[f * nm], xi[p], r);
          double scale = 1;
          for (int m = 0; m < nm; ++m) scale += std::fabs(c[f * nm + m]) * (1 + degree);
          worst = std::max(worst, static_cast<double>(std::fabs(value[f * n + p] - r[0])) / scale);
          for (int a = 0; a < 3; ++a) {
            const long double g = r[1] * j[a] + r[2] * j[3 + a] + r[3] * j[6 + a];
            worst = std::max(worst, static_cast<double>(std::fabs(gradient[(3 * f + a) * n + p] - g)) / (3 * scale));
          }
        }
    }
  }
  EXPECT_LE(worst, 1e-15);
}

// evaluate_gradient_sums: the same values bit for bit, and the weighted sums of the gradients along the
// points against long double sums of the exact reference derivatives (reference_sums) times j.
TEST(PolynomialValues3d, GradientSumsOfEveryDegreeWithTwinsAgainstWeightedReferenceSums) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> pick(0, 1);
  double worst = 0;
  for (int degree = 0; degree <= kMaxLatticeDegree; ++degree) {
    const int nm = monomial_count3(degree), width = kWidth, n = 17;
    const std::vector<double> c = sparse_and_dense(degree, gen);
    const int* twin = kTwin;
    const double j[9] = {0.8, -0.4, 0.3, 0.2, 1.7, -0.5, -0.6, 0.1, 1.1};
    std::vector<Point3> xi(n);
    std::vector<double> w(n);
    for (int p = 0; p < n; ++p) {
      xi[p] = {pick(gen), pick(gen), pick(gen)};
      w[p] = pick(gen);
    }
    for (bool with_twins : {false, true}) {
      const int* tw = with_twins ? twin : nullptr;
      PolynomialTerms3 terms(degree, c.data(), width);
      std::vector<double> value(static_cast<size_t>(width) * n), gradient(3 * value.size());
      terms.evaluate(tw, j, xi.data(), n, value.data(), gradient.data());
      std::vector<double> value2(value.size()), sums(3 * static_cast<size_t>(width)), once(value.size()),
          once_sums(sums.size());
      terms.evaluate_gradient_sums(tw, j, xi.data(), w.data(), n, value2.data(), sums.data());
      EXPECT_EQ(value2, value) << "degree " << degree;
      evaluate_polynomials3_gradient_sums(degree, c.data(), width, j, xi.data(), w.data(), n, once.data(),
                                          once_sums.data());
      EXPECT_EQ(once, value) << "degree " << degree;
      for (int f = 0; f < width; ++f) {
        long double exact[3] = {0, 0, 0};
        double scale = 1;
        for (int m = 0; m < nm; ++m) scale += std::fabs(c[f * nm + m]) * (1 + degree);
        for (int p = 0; p < n; ++p) {
          long double r[4];
          reference_sums(degree, &c[f * nm], xi[p], r);
          for (int a = 0; a < 3; ++a) exact[a] += w[p] * (r[1] * j[a] + r[2] * j[3 + a] + r[3] * j[6 + a]);
        }
        for (int a = 0; a < 3; ++a) {
          worst = std::max(worst, static_cast<double>(std::fabs(sums[3 * f + a] - exact[a])) / (3 * n * scale));
          worst = std::max(worst, std::fabs(once_sums[3 * f + a] - static_cast<double>(exact[a])) / (3 * n * scale));
        }
      }
    }
  }
  EXPECT_LE(worst, 1e-15);
}

TEST(PolynomialFit, A3dLatticeFitAboveTheBasisDegreeHasExactZeros) {
  // P2's functions fitted on the lattices of degree 2 to 8 (a rotated, stretched tetrahedron: the reference
  // functions are those of the reference tetrahedron whatever the element): the coefficients of the
  // monomials of degree above 2 must come out exactly zero, and the fit must still be P2.
  Mesh3 mesh = test3d::box_mesh(1, 1, 1, {0.3, -0.2, 0.1}, {1.7, 0.6, 2.3});
  mesh = test3d::moved(mesh, {1, 2, 3}, 0.4, {0, 0, 0}, {0, 0, 0});
  const test3d::P2Tet p2(mesh);
  for (int degree = 2; degree <= kMaxLatticeDegree; ++degree) {
    const PolynomialBasis3 fit(p2, mesh, degree, {0});
    ASSERT_TRUE(fit.fitted()) << degree;
    int nonzero = 0;
    for (size_t f = 0; f < fit.functions().size(); ++f)
      for (int m = monomial_count3(2); m < monomial_count3(degree); ++m)
        if (fit.coefficients(0)[f * monomial_count3(degree) + m] != 0) ++nonzero;
    EXPECT_EQ(nonzero, 0) << "degree " << degree;
    // and it still evaluates P2: values and physical gradients at a point of element 1
    const Point3 xi{0.21, 0.17, 0.33};
    std::vector<double> value(10), gradient(30), basis(40);
    fit.evaluate_points(1, &xi, 1, value.data(), gradient.data());
    p2.evaluate(1, xi, basis.data());
    for (int f = 0; f < 10; ++f) {
      EXPECT_NEAR(value[f], basis[4 * f], 1e-12);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(gradient[3 * f + a], basis[4 * f + 1 + a], 1e-11);
    }
  }
}

TEST(PolynomialFit, A2dLatticeFitAboveTheBasisDegreeHasExactZeros) {
  // P1 on a grid's triangles fitted on the lattices of degree 1 to 8: the monomials of degree 2 and up get
  // exactly zero, and the fit is still P1 at a point off the lattice.
  const Mesh mesh = test::grid_mesh(2, 2, -0.3, 0.2, 1.9, 0.7, true);
  const test::P1 p1(mesh);
  const int elements = static_cast<int>(mesh.triangles.size());
  for (int degree = 1; degree <= kMaxLatticeDegree; ++degree) {
    BasisFit fit(p1, elements, degree, {0});
    fit.fit_elements(elements);
    ASSERT_TRUE(fit.fitted()) << degree;
    const int nm = fit.terms();
    int nonzero = 0;
    double worst = 0;
    const Point xi{0.23, 0.41};
    double v[monomial_count(kMaxLatticeDegree)];
    monomial_values(degree, xi, v);
    for (size_t f = 0; f < fit.functions().size(); ++f) {
      const double* c = fit.coefficients(0) + f * nm;
      for (int m = monomial_count(1); m < nm; ++m) nonzero += c[m] != 0;
      double s = 0;
      for (int m = 0; m < nm; ++m) s += c[m] * v[m];
      const double lambda[3] = {1 - xi.x - xi.y, xi.x, xi.y};  // P1's functions in the reference triangle
      worst = std::max(worst, std::fabs(s - lambda[f]));
    }
    EXPECT_EQ(nonzero, 0) << "degree " << degree;
    EXPECT_LE(worst, 1e-12) << "degree " << degree;  // the lattice's |V^-1| grows with the degree: 1.4e-14 at 8
  }
}

namespace {

// P1 whose functions on element k are permuted (k % 3 == 1: the last two swapped) or negated (k % 3 == 2)
// against the barycentric coordinates, as an element whose dof order or signs depend on it: only elements
// 0, 3, 6, ... share element 0's polynomials.
class TwistedP1 : public Basis {
 public:
  explicit TwistedP1(const Mesh& m) : p1_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return p1_.dof_count(); }
  int local_dofs() const override { return 3; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 3; }
  void dofs(int k, int* g) const override { p1_.dofs(k, g); }
  void evaluate(int k, Point xi, double* out) const override {
    p1_.evaluate(k, xi, out);
    if (k % 3 == 1)
      for (int d = 0; d < 3; ++d) std::swap(out[3 + d], out[6 + d]);
    if (k % 3 == 2)
      for (int i = 0; i < 9; ++i) out[i] = -out[i];
  }

 private:
  test::P1 p1_;
};

}  // namespace

// Elements whose functions differ from element 0's get fits of their own (BasisFit's check at one point),
// the others share element 0's: the fitted basis gives the basis's values and gradients on every element.
TEST(PolynomialFit, ElementsThatDifferFromTheFirstGetTheirOwnFits) {
  const Mesh mesh = test::grid_mesh(4, 3, -0.3, 0.2, 1.9, 0.7, true);
  const TwistedP1 basis(mesh);
  const PolynomialBasis fit(basis, mesh, 1, {0});
  ASSERT_TRUE(fit.fitted());
  double got[9], want[9];
  for (int k = 0; k < mesh.size(); ++k) {
    EXPECT_EQ(fit.shared(k), k % 3 == 0) << "element " << k;
    for (const Point xi : {Point{0.1, 0.2}, Point{0.6, 0.3}}) {
      fit.evaluate(k, xi, got);
      basis.evaluate(k, xi, want);
      for (int i = 0; i < 9; ++i) EXPECT_NEAR(got[i], want[i], 1e-11 * (1 + std::fabs(want[i]))) << k << " " << i;
    }
  }
}

namespace {

// P1 on tetrahedra whose functions on element k are permuted (k % 3 == 1: the last two swapped) or negated
// (k % 3 == 2) against the barycentric coordinates: only elements 0, 3, 6, ... share element 0's polynomials.
class TwistedP1Tet : public Basis3 {
 public:
  explicit TwistedP1Tet(const Mesh3& m) : p1_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return p1_.dof_count(); }
  int local_dofs() const override { return 4; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 4; }
  void dofs(int k, int* g) const override { p1_.dofs(k, g); }
  void evaluate(int k, Point3 xi, double* out) const override {
    p1_.evaluate(k, xi, out);
    if (k % 3 == 1)
      for (int d = 0; d < 4; ++d) std::swap(out[8 + d], out[12 + d]);
    if (k % 3 == 2)
      for (int i = 0; i < 16; ++i) out[i] = -out[i];
  }

 private:
  test3d::P1Tet p1_;
};

}  // namespace

// The 3D fit's check (PolynomialBasis3: an element whose values at the check point are element 0's bit for
// bit shares its fit without the fit's sums): elements whose functions differ from element 0's get fits of
// their own, the others share it, and the fitted basis gives the basis's values and gradients on every one.
TEST(PolynomialFit, TetrahedraThatDifferFromTheFirstGetTheirOwnFits) {
  Mesh3 mesh = test3d::box_mesh(2, 2, 1, {0.3, -0.2, 0.1}, {1.7, 0.6, 2.3});
  mesh = test3d::moved(mesh, {1, 2, 3}, 0.4, {0, 0, 0}, {0, 0, 0});
  const TwistedP1Tet basis(mesh);
  const PolynomialBasis3 fit(basis, mesh, 1, {0});
  ASSERT_TRUE(fit.fitted());
  double got[16], want[16];
  for (int k = 0; k < mesh.size(); ++k) {
    EXPECT_EQ(fit.shared(k), k % 3 == 0) << "element " << k;
    for (const Point3 xi : {Point3{0.1, 0.2, 0.3}, Point3{0.5, 0.1, 0.2}}) {
      fit.evaluate(k, xi, got);
      basis.evaluate(k, xi, want);
      for (int i = 0; i < 16; ++i) EXPECT_NEAR(got[i], want[i], 1e-11 * (1 + std::fabs(want[i]))) << k << " " << i;
    }
  }
}
