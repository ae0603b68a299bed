// Results that do not depend on the units of the meshes: every integration path at mesh sizes 1e-120,
// 1e-6, 1, 1e6 and 1e120 against a reference integrated on the solid triangles (no clipping, no pull-back),
// and bit for bit between sizes that differ by a power of two.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "coupling/coupling.hpp"
#include "errors.hpp"
#include "fe/rules.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// X(s) = L F(s / L) with F(z) = A z + b + eps g(z): a rotation, plus
//  - kind Affine: nothing;
//  - kind Bubble: the cubic bubble 27 l0 l1 l2 of each solid triangle times (0.002, -0.0015) (nonlinearity
//    0.07: one rule per piece), StrongBubble times (0.0048, -0.0036) (nonlinearity 0.5: split images): straight
//    images;
//  - kind Quartic: z1 (1 - z1) z2 (1 - z2) (0.5, 0.25), which vanishes on the unit square's sides: curved
//    images inside, straight along the solid's boundary (so the chords of the curved path tile it exactly).
class ScaledTestMap : public SolidMap {
 public:
  enum Kind { Affine, Bubble, StrongBubble, Quartic };
  ScaledTestMap(const Mesh& solid, double scale, Kind kind) : solid_(solid), l_(scale), kind_(kind) {}
  int degree() const override { return kind_ == Affine ? 1 : (kind_ == Quartic ? 4 : 3); }
  MapValue evaluate(int k, Point xi) const override {
    Point c[3];
    solid_.corners(k, c);
    const Point s = from_reference(c, xi);
    const Point z{s.x / l_, s.y / l_};
    MapValue v;
    v.x = {l_ * (ca_ * z.x - sa_ * z.y + 0.05), l_ * (sa_ * z.x + ca_ * z.y - 0.02)};
    double j[2][2] = {{ca_, -sa_}, {sa_, ca_}};  // dF/dz = dX/ds
    if (kind_ == Bubble || kind_ == StrongBubble) {
      // b = 27 l0 l1 l2 in the reference coordinates; db/ds = db/dxi dxi/ds
      const double l0 = 1 - xi.x - xi.y, b = 27 * l0 * xi.x * xi.y;
      const double b1 = 27 * xi.y * (l0 - xi.x), b2 = 27 * xi.x * (l0 - xi.y);
      const Point e1 = c[1] - c[0], e2 = c[2] - c[0];
      const double det = cross(e1, e2);
      const double gx = (b1 * e2.y - b2 * e1.y) / det, gy = (b2 * e1.x - b1 * e2.x) / det;  // db/ds
      const double a = kind_ == Bubble ? 0.25 : 0.6, w[2] = {0.008 * a, -0.006 * a};
      for (int a = 0; a < 2; ++a) {
        (a == 0 ? v.x.x : v.x.y) += l_ * w[a] * b;
        j[a][0] += l_ * w[a] * gx;
        j[a][1] += l_ * w[a] * gy;
      }
    } else if (kind_ == Quartic) {
      const double g = z.x * (1 - z.x) * z.y * (1 - z.y);
      const double gx = (1 - 2 * z.x) * z.y * (1 - z.y), gy = z.x * (1 - z.x) * (1 - 2 * z.y);
      const double w[2] = {0.5, 0.25};
      for (int a = 0; a < 2; ++a) {
        (a == 0 ? v.x.x : v.x.y) += l_ * w[a] * g;
        j[a][0] += w[a] * gx;
        j[a][1] += w[a] * gy;
      }
    }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) v.jac[a][b] = j[a][b];
    return v;
  }

 private:
  const Mesh& solid_;
  double l_;
  Kind kind_;
  double ca_ = std::cos(0.3), sa_ = std::sin(0.3);
};

// (x / L)^9 on every fluid triangle (one dof each): a polynomial above the fitted degrees, so the assembly
// evaluates it point by point.
class ScaledPowerNine : public Basis {
 public:
  ScaledPowerNine(const Mesh& m, double scale) : m_(m), l_(scale) {}
  int components() const override { return 1; }
  int dof_count() const override { return m_.size(); }
  int local_dofs() const override { return 1; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 1; }
  void dofs(int k, int* g) const override { g[0] = k; }
  void evaluate(int k, Point xi, double* out) const override {
    Point c[3];
    m_.corners(k, c);
    const double x = from_reference(c, xi).x / l_;
    out[0] = std::pow(x, 9);
    out[1] = 9 * std::pow(x, 8) / l_;
    out[2] = 0;
  }

 private:
  const Mesh& m_;
  double l_;
};

double form(const CsrMatrix& b, const std::vector<double>& lam, const std::vector<double>& u) {
  double s = 0;
  for (int i = 0; i < b.rows; ++i)
    for (int e = b.start[i]; e < b.start[i + 1]; ++e) s += lam[i] * b.value[e] * u[b.column[e]];
  return s;
}

struct Case {
  Mesh fluid, solid;
  double scale;
};

// Fluid [-1, 1.5]^2 and solid [0, 1]^2 (the quartic's square), both times the scale.
Case make_case(double scale) {
  return {test::grid_mesh(11, 9, -scale, -scale, 2.5 * scale, 2.5 * scale, true),
          test::grid_mesh(5, 4, 0, 0, scale, scale), scale};
}

// c2 int lam u(X) + c1 grad_s lam . (dX/ds^T grad_y u) over the solid, for fluid data u (value, gradient)
// and multiplier data lam (value, gradient) given as functions of the physical point, integrated on the
// solid triangles with a rule of degree 12 (exact for these polynomials).
template <class U, class Lam>
double reference(const Case& c, const SolidMap& map, double c1, double c2, U u, Lam lam) {
  long double sum = 0;
  for (int k = 0; k < c.solid.size(); ++k) {
    Point p[3];
    c.solid.corners(k, p);
    const double area = 0.5 * area2(p[0], p[1], p[2]);
    for (const RulePoint& q : triangle_rule(12)) {
      const MapValue v = map.evaluate(k, q.xi);
      double uv, ug[2], lv, lg[2];
      u(v.x, uv, ug);
      lam(from_reference(p, q.xi), lv, lg);
      const double gx = v.jac[0][0] * ug[0] + v.jac[1][0] * ug[1], gy = v.jac[0][1] * ug[0] + v.jac[1][1] * ug[1];
      sum += static_cast<long double>(area * q.weight) * (c2 * lv * uv + c1 * (lg[0] * gx + lg[1] * gy));
    }
  }
  return static_cast<double>(sum);
}

const double kScales[] = {1e-120, 1e-6, 1, 1e6, 1e120};

// Global linear data in units of the scale: u = 1 + 0.3 x/L - 0.7 y/L, lam = 0.2 - x/L + 0.5 y/L.
struct LinearData {
  std::vector<double> u, lam;
  double l;
  LinearData(const Case& c) : l(c.scale) {
    for (Point p : c.fluid.vertices) u.push_back(1 + 0.3 * p.x / l - 0.7 * p.y / l);
    for (Point p : c.solid.vertices) lam.push_back(0.2 - p.x / l + 0.5 * p.y / l);
  }
  void fluid(Point x, double& v, double g[2]) const {
    v = 1 + 0.3 * x.x / l - 0.7 * x.y / l;
    g[0] = 0.3 / l;
    g[1] = -0.7 / l;
  }
  void multiplier(Point s, double& v, double g[2]) const {
    v = 0.2 - s.x / l + 0.5 * s.y / l;
    g[0] = -1 / l;
    g[1] = 0.5 / l;
  }
};

// One path at every scale: lambda' B u against the reference, to tol relative.
void check_path(ScaledTestMap::Kind kind, CouplingOptions opt, double tol, const char* path) {
  for (double scale : kScales) {
    const Case c = make_case(scale);
    const ScaledTestMap map(c.solid, scale, kind);
    const test::P1 vf(c.fluid), vs(c.solid);
    const LinearData d(c);
    CouplingReport rep;
    const CsrMatrix b = assemble_coupling(c.fluid, vf, c.solid, vs, map, opt, &rep);
    const double want = reference(
        c, map, opt.c1, opt.c2, [&](Point x, double& v, double* g) { d.fluid(x, v, g); },
        [&](Point s, double& v, double* g) { d.multiplier(s, v, g); });
    const double got = form(b, d.lam, d.u);
    EXPECT_NEAR(got, want, tol * std::fabs(want)) << path << " at scale " << scale;
    EXPECT_LE(rep.outside_measure, 1e-14 * rep.image_measure) << path << " at scale " << scale;
  }
}

CouplingOptions both_terms() {
  CouplingOptions opt;
  opt.c1 = 0.7;
  opt.c2 = 3;
  return opt;
}

}  // namespace

TEST(Scale, LinearPathAffineMap) { check_path(ScaledTestMap::Affine, both_terms(), 1e-13, "linear"); }

TEST(Scale, NewtonPathBubbleMap) { check_path(ScaledTestMap::Bubble, both_terms(), 1e-12, "Newton (straight)"); }

TEST(Scale, SplitPathStrongBubbleMap) {
  check_path(ScaledTestMap::StrongBubble, both_terms(), 1e-12, "split (straight, far from affine)");
}

TEST(Scale, CurvedPathQuarticMap) { check_path(ScaledTestMap::Quartic, both_terms(), 1e-12, "curved"); }

TEST(Scale, QuadratureMethod) {
  CouplingOptions opt = both_terms();
  opt.method = CouplingOptions::Method::Quadrature;
  check_path(ScaledTestMap::Affine, opt, 1e-13, "quadrature, affine");
  check_path(ScaledTestMap::Bubble, opt, 1e-12, "quadrature, bubble");
}

// The point-by-point path (an unfitted fluid basis), mass term: sum_ij B_ij = int_solid (X_1 / L)^9 ds. The
// fluid triangles are large, so that the probe of the basis's degree sees the ninth differences.
TEST(Scale, PointPathUnfittedBasis) {
  for (double scale : kScales) {
    Case c = make_case(scale);
    c.fluid = test::grid_mesh(3, 3, -scale, -scale, 2.5 * scale, 2.5 * scale, true);
    const ScaledTestMap map(c.solid, scale, ScaledTestMap::Affine);
    const ScaledPowerNine vf(c.fluid, scale);
    const test::P1 vs(c.solid);
    CouplingOptions opt;
    opt.c1 = 0;
    opt.c2 = 1;
    CouplingReport rep;
    const CsrMatrix b = assemble_coupling(c.fluid, vf, c.solid, vs, map, opt, &rep);
    EXPECT_EQ(rep.fluid_degree, 9);
    const double want = reference(
        c, map, 0, 1,
        [&](Point x, double& v, double* g) {
          v = std::pow(x.x / scale, 9);
          g[0] = g[1] = 0;
        },
        [](Point, double& v, double* g) {
          v = 1;
          g[0] = g[1] = 0;
        });
    const std::vector<double> one_f(c.fluid.size(), 1), one_s(c.solid.vertices.size(), 1);
    EXPECT_NEAR(form(b, one_s, one_f), want, 1e-13 * std::fabs(want)) << "scale " << scale;
  }
}

// Sizes that differ by a power of two give the same matrix times that power squared (mass term) or the
// same matrix (gradient term), bit for bit: the scaling is exact.
TEST(Scale, PowersOfTwoGiveTheSameBits) {
  for (ScaledTestMap::Kind kind : {ScaledTestMap::Affine, ScaledTestMap::Bubble}) {
    std::vector<std::vector<double>> values[2];
    for (int e : {0, 400, -400}) {
      const double scale = std::ldexp(1.0, e);
      const Case c = make_case(scale);
      const ScaledTestMap map(c.solid, scale, kind);
      const test::P1 vf(c.fluid), vs(c.solid);
      for (int term = 0; term < 2; ++term) {
        CouplingOptions opt;
        opt.c1 = term;
        opt.c2 = 1 - term;
        const CsrMatrix m = assemble_coupling(c.fluid, vf, c.solid, vs, map, opt);
        std::vector<double> v(m.value.begin(), m.value.end());
        for (double& x : v) x = std::ldexp(x, term == 0 ? -2 * e : 0);
        values[term].push_back(v);
      }
    }
    for (int term = 0; term < 2; ++term) {
      EXPECT_EQ(values[term][0], values[term][1]) << "kind " << kind << " term " << term;
      EXPECT_EQ(values[term][0], values[term][2]) << "kind " << kind << " term " << term;
    }
  }
}

// Solid triangles too small or too large for double products of their gradients and areas: an error that
// says so, never NaN.
TEST(Scale, SolidTrianglesBeyondTheRangeAreAnError) {
  for (double scale : {1e-160, 1e160}) {
    const Case c = make_case(scale);
    const ScaledTestMap map(c.solid, scale, ScaledTestMap::Affine);
    const test::P1 vf(c.fluid), vs(c.solid);
    try {
      assemble_coupling(c.fluid, vf, c.solid, vs, map, CouplingOptions());
      ADD_FAILURE() << "no error at scale " << scale;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("solid triangles from about 1e-150 to 1e150"), std::string::npos) << e.what();
    }
  }
}
