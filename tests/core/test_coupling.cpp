#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/clip.hpp"
#include "coupling/coupling.hpp"
#include "errors.hpp"
#include "fe/rules.hpp"
#include "support.hpp"

using namespace dlmfsi;

namespace {

// lambda^T B u for nodal vectors.
double form(const CsrMatrix& b, const std::vector<double>& lam, const std::vector<double>& u) {
  double s = 0;
  for (int i = 0; i < b.rows; ++i)
    for (int e = b.start[i]; e < b.start[i + 1]; ++e) s += lam[i] * b.value[e] * u[b.column[e]];
  return s;
}

struct Rotation {
  double c, s, bx, by;
  Point operator()(Point p) const { return {c * p.x - s * p.y + bx, s * p.x + c * p.y + by}; }
};

// Brute force over every (solid, fluid) pair, no search: the solid triangle's image (corners mapped by image)
// clipped against each fluid triangle, a degree-2 rule on each piece's fan, and at each point
// integrand(ks, kf, xs, xf) with the point's reference coordinates in the image and in the fluid triangle.
template <class Image, class Integrand>
long double brute_force(const Mesh& fluid, const Mesh& solid, Image image, Integrand integrand) {
  long double sum = 0;
  for (int ks = 0; ks < solid.size(); ++ks) {
    Point sc[3], ic[3];
    solid.corners(ks, sc);
    for (int i = 0; i < 3; ++i) ic[i] = image(sc[i]);
    for (int kf = 0; kf < fluid.size(); ++kf) {
      Point fc[3];
      fluid.corners(kf, fc);
      const Piece p = clip(ic, fc);
      for (int t = 1; t + 1 < p.n; ++t) {
        const Point tri[3] = {p.v[0], p.v[t], p.v[t + 1]};
        const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
        for (const auto& q : triangle_rule(2)) {
          const Point y = from_reference(tri, q.xi);
          sum += area * q.weight * integrand(ks, kf, to_reference(ic, y), to_reference(fc, y));
        }
      }
    }
  }
  return sum;
}

// n values uniform in [-1, 1] (nodal data with kinks on every edge)
std::vector<double> random_values(size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng);
  return v;
}

// A P1 function's value at reference point xi of triangle k from its nodal values.
double p1_value(const Mesh& mesh, const std::vector<double>& nodal, int k, Point xi) {
  const auto& t = mesh.triangles[k];
  return nodal[t[0]] * (1 - xi.x - xi.y) + nodal[t[1]] * xi.x + nodal[t[2]] * xi.y;
}

}  // namespace

// Linear data on both sides, affine map: u o X is linear on each solid triangle, so a degree-2 rule on the
// solid triangles (no clipping) is an independent exact reference.
TEST(Coupling, LinearDataUnderRotationIsExact) {
  Mesh fluid = test::grid_mesh(17, 13, -1, -1, 2, 2, true);
  Mesh solid = test::grid_mesh(9, 7, -0.4, -0.3, 0.8, 0.6);
  const double angle = 0.3;
  Rotation r{std::cos(angle), std::sin(angle), 0.05, -0.02};
  test::AffineMap map(solid, r.c, -r.s, r.s, r.c, r.bx, r.by);
  test::P1 vf(fluid), vs(solid);
  auto u = [](Point x) { return 1.5 + 2 * x.x - 0.7 * x.y; };
  auto lam = [](Point s) { return -0.3 + s.x + 3 * s.y; };
  std::vector<double> uh, lh;
  for (Point p : fluid.vertices) uh.push_back(u(p));
  for (Point p : solid.vertices) lh.push_back(lam(p));
  for (double c1 : {0.0, 1.0}) {
    CouplingOptions opt;
    opt.c1 = c1;
    opt.c2 = 10;
    CouplingReport rep;
    CsrMatrix b = assemble_coupling(fluid, vf, solid, vs, map, opt, &rep);
    // reference: c2 int lam u(X) + c1 grad lam . grad(u o X) with grad(u o X) = A^T grad u
    const double gu[2] = {2, -0.7};
    const double gux = r.c * gu[0] + r.s * gu[1], guy = -r.s * gu[0] + r.c * gu[1];
    double want = 0;
    for (int k = 0; k < solid.size(); ++k) {
      Point c[3];
      solid.corners(k, c);
      const double area = 0.5 * area2(c[0], c[1], c[2]);
      for (const auto& q : triangle_rule(2)) {
        Point s = from_reference(c, q.xi);
        want += area * q.weight * (opt.c2 * lam(s) * u(r(s)) + c1 * (1 * gux + 3 * guy));
      }
    }
    EXPECT_NEAR(form(b, lh, uh), want, 1e-12 * std::fabs(want));
    EXPECT_LT(rep.outside_measure, 1e-14 * rep.image_measure);
  }
}

TEST(Coupling, OnesGiveTheSolidArea) {
  Mesh fluid = test::grid_mesh(10, 10, 0, 0, 1, 1);
  Mesh solid = test::grid_mesh(4, 4, 0.2, 0.2, 0.5, 0.5);  // vertices on fluid vertices, edges on fluid edges
  test::AffineMap id(solid, 1, 0, 0, 1, 0, 0);
  test::P1 vf(fluid), vs(solid);
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  CsrMatrix b = assemble_coupling(fluid, vf, solid, vs, id, opt);
  std::vector<double> one_f(fluid.vertices.size(), 1), one_s(solid.vertices.size(), 1);
  EXPECT_NEAR(form(b, one_s, one_f), 0.25, 1e-15);
}

TEST(Coupling, KinkedDataMatchesBruteForceSupermesh) {
  // Random nodal values (kinks on fluid edges); reference by clipping every pair of triangles (all pairs,
  // no search) and a degree-2 rule on each piece.
  Mesh fluid = test::grid_mesh(6, 5, 0, 0, 1, 1, true);
  Mesh solid = test::grid_mesh(3, 3, 0.25, 0.2, 0.45, 0.5);
  test::AffineMap map(solid, std::cos(0.7), -std::sin(0.7), std::sin(0.7), std::cos(0.7), 0.3, -0.2);
  test::P1 vf(fluid), vs(solid);
  const std::vector<double> uh = random_values(fluid.vertices.size(), 5), lh = random_values(solid.vertices.size(), 105);
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  CsrMatrix b = assemble_coupling(fluid, vf, solid, vs, map, opt);
  const double c = std::cos(0.7), sn = std::sin(0.7);
  const double want = static_cast<double>(brute_force(
      fluid, solid, [&](Point p) { return Point{c * p.x - sn * p.y + 0.3, sn * p.x + c * p.y - 0.2}; },
      [&](int ks, int kf, Point xs, Point xf) {  // det of a rotation is 1
        return p1_value(fluid, uh, kf, xf) * p1_value(solid, lh, ks, xs);
      }));
  EXPECT_NEAR(form(b, lh, uh), want, 1e-13 * std::fabs(want) + 1e-15);
}

// The same brute force with both terms and a map that is not a rigid motion (shear and stretch, det 1.38):
// c2 lam u(X) / 1 + c1 grad_s lam . (A^T grad_y u), integrated over the pieces in the fluid with ds = dy / det A.
// The gradients come from each triangle's nodal values by solving the 2 x 2 system of its edges.
TEST(Coupling, KinkedDataUnderShearMatchesBruteForceWithGradients) {
  Mesh fluid = test::grid_mesh(7, 6, -0.2, -0.3, 1.5, 1.4, true);
  Mesh solid = test::grid_mesh(4, 3, 0.25, 0.2, 0.45, 0.5);
  const double a[2][2] = {{1.1, 0.35}, {-0.2, 1.19}}, det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  test::AffineMap map(solid, a[0][0], a[0][1], a[1][0], a[1][1], 0.05, -0.1);
  test::P1 vf(fluid), vs(solid);
  const std::vector<double> uh = random_values(fluid.vertices.size(), 11), lh = random_values(solid.vertices.size(), 111);
  auto gradient = [](const Point c[3], const double v[3]) {
    const Point e1 = c[1] - c[0], e2 = c[2] - c[0];
    const double d = cross(e1, e2), g1 = v[1] - v[0], g2 = v[2] - v[0];
    return Point{(g1 * e2.y - g2 * e1.y) / d, (g2 * e1.x - g1 * e2.x) / d};
  };
  CouplingOptions opt;
  opt.c1 = 0.7;
  opt.c2 = 3;
  CouplingReport rep;
  CsrMatrix b = assemble_coupling(fluid, vf, solid, vs, map, opt, &rep);
  EXPECT_LT(rep.outside_measure, 1e-14 * rep.image_measure);
  auto nodal = [](const Mesh& mesh, const std::vector<double>& v, int k, double out[3], Point corner[3]) {
    mesh.corners(k, corner);
    for (int i = 0; i < 3; ++i) out[i] = v[mesh.triangles[k][i]];
  };
  const long double want = brute_force(
      fluid, solid, [&](Point p) { return Point{a[0][0] * p.x + a[0][1] * p.y + 0.05, a[1][0] * p.x + a[1][1] * p.y - 0.1}; },
      [&](int ks, int kf, Point xs, Point xf) {
        double ls[3], uf[3];
        Point sc[3], fc[3];
        nodal(solid, lh, ks, ls, sc);
        nodal(fluid, uh, kf, uf, fc);
        const Point gl = gradient(sc, ls), gu = gradient(fc, uf);
        const Point gs{a[0][0] * gu.x + a[1][0] * gu.y, a[0][1] * gu.x + a[1][1] * gu.y};  // A^T grad u
        return (opt.c2 * p1_value(fluid, uh, kf, xf) * p1_value(solid, lh, ks, xs) +
                opt.c1 * (gl.x * gs.x + gl.y * gs.y)) / det;
      });
  EXPECT_NEAR(form(b, lh, uh), static_cast<double>(want), 1e-13 * std::fabs(static_cast<double>(want)));
}

TEST(CouplingErrors, OutsideTheFluidIsAnErrorUnlessDropped) {
  Mesh fluid = test::grid_mesh(4, 4, 0, 0, 1, 1);
  Mesh solid = test::grid_mesh(2, 2, 0.8, 0.4, 0.4, 0.2);
  test::AffineMap id(solid, 1, 0, 0, 1, 0, 0);
  test::P1 vf(fluid), vs(solid);
  CouplingOptions opt;
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, id, opt), Error);
  opt.drop_outside = true;
  CouplingReport rep;
  assemble_coupling(fluid, vf, solid, vs, id, opt, &rep);
  EXPECT_NEAR(rep.outside_measure, 0.2 * 0.2, 1e-15);
  EXPECT_NEAR(rep.image_measure, 0.4 * 0.2, 1e-15);
}

TEST(CouplingErrors, ReflectionAndFlatMapsAreErrors) {
  Mesh fluid = test::grid_mesh(4, 4, -1, -1, 2, 2);
  Mesh solid = test::grid_mesh(2, 2, -0.2, -0.2, 0.4, 0.4);
  test::P1 vf(fluid), vs(solid);
  CouplingOptions opt;
  test::AffineMap mirror(solid, -1, 0, 0, 1, 0, 0), flat(solid, 1, 1, 1, 1, 0, 0),
      nan(solid, std::nan(""), 0, 0, 1, 0, 0);
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, mirror, opt), Error);
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, flat, opt), Error);
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, nan, opt), Error);
  opt.fluid_components = {0, 0};
  test::AffineMap id(solid, 1, 0, 0, 1, 0, 0);
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, id, opt), Error);  // lengths differ
  opt.solid_components = {0, 1};
  EXPECT_THROW(assemble_coupling(fluid, vf, solid, vs, id, opt), Error);  // component out of range
}

TEST(Coupling, ThreadsGiveTheSameMatrix) {
  Mesh fluid = test::grid_mesh(20, 20, 0, 0, 1, 1, true);
  Mesh solid = test::grid_mesh(15, 11, 0.2, 0.25, 0.5, 0.4);
  test::AffineMap map(solid, std::cos(0.2), -std::sin(0.2), std::sin(0.2), std::cos(0.2), 0.05, 0);
  test::P1 vf(fluid), vs(solid);
  CouplingOptions opt;
  CsrMatrix one = assemble_coupling(fluid, vf, solid, vs, map, opt);
  opt.threads = 3;
  CsrMatrix three = assemble_coupling(fluid, vf, solid, vs, map, opt);
  EXPECT_EQ(one.column, three.column);
  EXPECT_EQ(one.value, three.value);
}

TEST(Coupling, QuadratureMethodConvergesToTheExactValue) {
  Mesh fluid = test::grid_mesh(12, 12, 0, 0, 1, 1, true);
  Mesh solid = test::grid_mesh(3, 3, 0.3, 0.3, 0.4, 0.4);
  test::AffineMap map(solid, std::cos(0.4), -std::sin(0.4), std::sin(0.4), std::cos(0.4), 0.1, -0.1);
  test::P1 vf(fluid), vs(solid);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> uh(fluid.vertices.size()), lh(solid.vertices.size());
  for (auto& v : uh) v = u(rng);
  for (auto& v : lh) v = u(rng);
  CouplingOptions opt;
  const double exact = form(assemble_coupling(fluid, vf, solid, vs, map, opt), lh, uh);
  opt.method = CouplingOptions::Method::Quadrature;
  double previous = 1e300;
  for (double tol : {1e-2, 1e-4, 1e-6}) {
    opt.tol = tol;
    const double err = std::fabs(form(assemble_coupling(fluid, vf, solid, vs, map, opt), lh, uh) - exact);
    EXPECT_LT(err, previous);
    previous = err;
  }
  EXPECT_LT(previous, 1e-3 * std::fabs(exact));
}

namespace {

// One function per fluid triangle, x^9 (physical x): a polynomial above the degree the bases are fitted to
// (8), so the assembly evaluates it point by point rather than in batches.
class PowerNine : public Basis {
 public:
  explicit PowerNine(const Mesh& m) : m_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return m_.size(); }
  int local_dofs() const override { return 1; }
  void component_dofs(int, int& f, int& l) const override { f = 0; l = 1; }
  void dofs(int k, int* g) const override { g[0] = k; }
  void evaluate(int k, Point xi, double* out) const override {
    Point c[3];
    m_.corners(k, c);
    const double x = from_reference(c, xi).x;
    out[0] = std::pow(x, 9);
    out[1] = 9 * std::pow(x, 8);
    out[2] = 0;
  }

 private:
  const Mesh& m_;
};

}  // namespace

// The point-by-point path (a basis that is not fitted): sum_ij B_ij = int over the mapped solid of x^9,
// which Green's theorem gives independently as the boundary integral of x^10/10 dy, exact for the
// polygon X(solid) (the solid is a rotated rectangle).
TEST(Coupling, UnfittedBasisIntegratesExactly) {
  Mesh fluid = test::grid_mesh(3, 2, 0, 0, 1.1, 0.9, true);  // large pieces: a rule of too low a degree shows
  Mesh solid = test::grid_mesh(2, 2, 0.35, 0.3, 0.4, 0.3);
  const double angle = 0.4;
  Rotation r{std::cos(angle), std::sin(angle), 0.25, -0.2};
  test::AffineMap map(solid, r.c, -r.s, r.s, r.c, r.bx, r.by);
  PowerNine vf(fluid);
  test::P1 vs(solid);
  CouplingOptions opt;
  opt.c1 = 0;
  opt.c2 = 1;
  CouplingReport rep;
  const CsrMatrix b = assemble_coupling(fluid, vf, solid, vs, map, opt, &rep);
  EXPECT_EQ(rep.fluid_degree, 9);
  std::vector<double> one_f(fluid.size(), 1), one_s(solid.vertices.size(), 1);
  // counter-clockwise corners of the mapped rectangle [0.35, 0.75] x [0.3, 0.6]
  const Point corner[4] = {r({0.35, 0.3}), r({0.75, 0.3}), r({0.75, 0.6}), r({0.35, 0.6})};
  long double want = 0;
  for (int e = 0; e < 4; ++e) {
    // int_edge x^10/10 dy with x, y linear along the edge: exact by 6-point Gauss-Legendre
    const Point p = corner[e], q = corner[(e + 1) % 4];
    const long double nodes[3] = {0.2386191860831969086305017L, 0.6612093864662645136613996L, 0.9324695142031520278123016L};
    const long double weights[3] = {0.4679139345726910473898703L, 0.3607615730481386075698335L, 0.1713244923791703450402961L};
    for (int g = 0; g < 3; ++g)
      for (int sgn : {-1, 1}) {
        const long double t = 0.5L + 0.5L * sgn * nodes[g];
        const long double x = p.x + t * (q.x - p.x);
        want += 0.5L * weights[g] * std::pow(x, 10) / 10 * (q.y - p.y);
      }
  }
  EXPECT_NEAR(form(b, one_s, one_f), static_cast<double>(want), 1e-14 * std::fabs(static_cast<double>(want)));
}
