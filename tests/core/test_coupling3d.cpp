// The 3D coupling assembly against independent references: 1'B1 = the solid's volume on fluid meshes that
// contain the solid's boundary; polynomial data under rotated and sheared affine maps against the integral
// computed on the solid mesh; the identity map against the mass and stiffness matrices assembled
// independently; bad input as errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "coupling/coupling3d.hpp"
#include "errors.hpp"
#include "fe/rules.hpp"
#include "support3d.hpp"

using namespace dlmfsi;
using namespace dlmfsi::test3d;

namespace {

const double kIdentity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

CsrMatrix couple(const Mesh3& fluid, const Basis3& fluid_space, const Mesh3& solid, const Basis3& multiplier,
                 const SolidMap3& map, double c1, double c2, CouplingReport* report = nullptr, int threads = 1,
                 std::vector<int> fc = {0}, std::vector<int> sc = {0},
                 CouplingOptions::Method method = CouplingOptions::Method::Exact) {
  CouplingOptions opt;
  opt.method = method;
  opt.c1 = c1;
  opt.c2 = c2;
  opt.threads = threads;
  opt.fluid_components = fc;
  opt.solid_components = sc;
  const FluidSide3 fs(fluid, fluid_space, fc);
  const SolidSide3 ss(solid, multiplier, sc);
  return assemble_coupling(fs, ss, map, opt, report);
}

double exact_volume(const Mesh3& m) {
  double v = 0;
  for (int k = 0; k < m.size(); ++k) {
    Point3 p[4];
    m.corners(k, p);
    v += volume6(p[0], p[1], p[2], p[3]) / 6;
  }
  return v;
}

// int over the solid of c2 L(s) U(X(s)) + c1 grad L . A^T grad U(X(s)), by a degree-8 rule on each solid
// tetrahedron (exact for these polynomials).
using Field = std::function<double(Point3)>;
using Gradient = std::function<Point3(Point3)>;
double reference(const Mesh3& solid, const AffineMap3& map, const double a[3][3], const Field& l, const Gradient& gl,
                 const Field& u, const Gradient& gu, double c1, double c2) {
  double s = 0;
  for (int k = 0; k < solid.size(); ++k) {
    Point3 p[4];
    solid.corners(k, p);
    const double vol = volume6(p[0], p[1], p[2], p[3]) / 6;
    for (const RulePoint3& q : tetrahedron_rule(8)) {
      const Point3 x = from_reference(p, q.xi), y = map.apply(x);
      const Point3 g = gu(y);
      const Point3 chain{a[0][0] * g.x + a[1][0] * g.y + a[2][0] * g.z, a[0][1] * g.x + a[1][1] * g.y + a[2][1] * g.z,
                         a[0][2] * g.x + a[1][2] * g.y + a[2][2] * g.z};  // grad_s (U o X) = A^T grad U
      s += vol * q.weight * (c2 * l(x) * u(y) + c1 * dot(gl(x), chain));
    }
  }
  return s;
}

// A rotation by 0.83 about (1, 2, 3) after a shear: the affine part of the polynomial tests' map.
void rotated_shear(double a[3][3]) {
  double r[3][3];
  rotation({1, 2, 3}, 0.83, r);
  const double shear[3][3] = {{1, 0.3, 0}, {0, 1.1, 0.2}, {0.1, 0, 0.9}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = r[i][0] * shear[0][j] + r[i][1] * shear[1][j] + r[i][2] * shear[2][j];
}
// Quadratic data in the fluid (u2) and in the solid (l2), with their gradients.
const Field u2 = [](Point3 y) { return 1 + 0.3 * y.x - 0.7 * y.y + 0.2 * y.z + y.x * y.y - 0.5 * y.z * y.z + 0.4 * y.x * y.x; };
const Gradient gu2 = [](Point3 y) { return Point3{0.3 + y.y + 0.8 * y.x, -0.7 + y.x, 0.2 - y.z}; };
const Field l2 = [](Point3 s) { return 1 + s.x * s.z - 0.3 * s.y * s.y; };
const Gradient gl2 = [](Point3 s) { return Point3{s.z, -0.6 * s.y, s.x}; };

template <class Space>
std::vector<double> interpolate(const Space& space, const Field& f) {
  std::vector<double> v(space.dof_count());
  for (int i = 0; i < space.dof_count(); ++i) v[i] = f(space.node(i));
  return v;
}

// P2 with the edge dofs listed in reverse on odd tetrahedra: the same space, but those elements' local
// functions differ from element 0's, so they do not share its fit (PolynomialBasis3::shared) and take the
// integrators' own-fit paths.
class P2TetReversedOnOdd : public Basis3 {
 public:
  explicit P2TetReversedOnOdd(const Mesh3& m) : p2_(m) {}
  int components() const override { return 1; }
  int dof_count() const override { return p2_.dof_count(); }
  int local_dofs() const override { return 10; }
  void component_dofs(int c, int& f, int& l) const override { p2_.component_dofs(c, f, l); }
  void dofs(int k, int* g) const override {
    p2_.dofs(k, g);
    if (k % 2) std::reverse(g + 4, g + 10);
  }
  void evaluate(int k, Point3 xi, double* out) const override {
    p2_.evaluate(k, xi, out);
    if (k % 2)
      for (int i = 0; i < 3; ++i) std::swap_ranges(out + 4 * (4 + i), out + 4 * (5 + i), out + 4 * (9 - i));
  }
  Point3 node(int dof) const { return p2_.node(dof); }

 private:
  P2Tet p2_;
};

}  // namespace

TEST(Coupling3d, VolumeOnFluidMeshesContainingTheSolidBoundary) {
  // fluid [0,1]^3 with grid planes at 0.25 and 0.75: the solid box [0.25,0.75]^3 has its faces on fluid faces
  const Mesh3 fluid = box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1});
  const Mesh3 fluid_jitter = box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1}, 0.0);
  const Mesh3 solids[] = {box_mesh(3, 3, 3, {0.25, 0.25, 0.25}, {0.5, 0.5, 0.5}),
                          box_mesh(2, 3, 5, {0.25, 0.25, 0.25}, {0.5, 0.5, 0.5}, 0.3, 11),
                          box_mesh(4, 4, 4, {0, 0, 0}, {1, 1, 1}),  // the fluid mesh itself
                          box_mesh(2, 2, 2, {0, 0, 0}, {1, 0.5, 0.25})};  // a corner of the fluid box
  for (const Mesh3& solid : solids) {
    const P1Tet fp1(fluid), sp1(solid);
    const P2Tet fp2(fluid), sp2(solid);
    const AffineMap3 identity(solid, kIdentity, {0, 0, 0});
    const double volume = exact_volume(solid);
    for (int pairing = 0; pairing < 3; ++pairing) {
      const Basis3& f = pairing == 1 ? static_cast<const Basis3&>(fp2) : fp1;
      const Basis3& s = pairing == 2 ? static_cast<const Basis3&>(sp2) : sp1;
      CouplingReport report;
      const CsrMatrix b = couple(fluid, f, solid, s, identity, 0, 1, &report);
      double sum = 0;
      for (double v : b.value) sum += v;
      EXPECT_NEAR(sum, volume, 1e-13 * volume) << "pairing " << pairing << ": " << report.summary();
      EXPECT_LE(report.outside_measure, 1e-15 * volume);  // round-off of the pieces against their image
    }
  }
}

TEST(Coupling3d, PolynomialExactnessUnderRotatedShearedMaps) {
  const Mesh3 fluid = box_mesh(5, 5, 5, {-1, -1, -1}, {2, 2, 2}, 0.25, 3);
  const Mesh3 solid = box_mesh(3, 2, 4, {-0.3, -0.3, -0.3}, {0.6, 0.6, 0.6}, 0.2, 4);
  double a[3][3];
  rotated_shear(a);
  const AffineMap3 map(solid, a, {0.05, -0.1, 0.07});
  // U quadratic (u2) or linear in the fluid, L linear or quadratic (l2) in the solid
  const Field u1 = [](Point3 y) { return 0.5 - 0.2 * y.x + 0.9 * y.y + 0.6 * y.z; };
  const Gradient gu1 = [](Point3) { return Point3{-0.2, 0.9, 0.6}; };
  const Field l1 = [](Point3 s) { return 2 - s.x + 0.5 * s.y + 0.25 * s.z; };
  const Gradient gl1 = [](Point3) { return Point3{-1, 0.5, 0.25}; };
  const P1Tet fp1(fluid), sp1(solid);
  const P2Tet fp2(fluid), sp2(solid);
  const P2TetReversedOnOdd fp2_own(fluid);
  struct Case {
    const char* name;
    bool fluid_p2, solid_p2, own_fits = false;
  };
  for (const Case& c : {Case{"P1 x P1", false, false}, Case{"P2 x P1", true, false}, Case{"P1 x P2", false, true},
                        Case{"P2 x P2", true, true}, Case{"P2 (own fits on odd elements) x P1", true, false, true}}) {
    const Field& u = c.fluid_p2 ? u2 : u1;
    const Gradient& gu = c.fluid_p2 ? gu2 : gu1;
    const Field& l = c.solid_p2 ? l2 : l1;
    const Gradient& gl = c.solid_p2 ? gl2 : gl1;
    const std::vector<double> uv = c.fluid_p2 ? interpolate(fp2, u) : interpolate(fp1, u);
    const std::vector<double> lv = c.solid_p2 ? interpolate(sp2, l) : interpolate(sp1, l);
    const Basis3& fs = c.own_fits ? static_cast<const Basis3&>(fp2_own) : c.fluid_p2 ? static_cast<const Basis3&>(fp2) : fp1;
    const Basis3& ss = c.solid_p2 ? static_cast<const Basis3&>(sp2) : sp1;
    for (double c1 : {0.0, 1.0}) {
      CouplingReport report;
      const CsrMatrix b = couple(fluid, fs, solid, ss, map, c1, 1, &report);
      const double exact = reference(solid, map, a, l, gl, u, gu, c1, 1);
      EXPECT_NEAR(bilinear(b, lv, uv), exact, 1e-13 * std::fabs(exact)) << c.name << " c1 = " << c1 << ": " << report.summary();
      EXPECT_GT(report.pieces, 3 * solid.size());  // the image crosses many fluid faces
    }
  }
}

TEST(Coupling3d, IdentityMapGivesMassAndStiffness) {
  // solid mesh = fluid mesh (jittered), identity map: B = c2 M + c1 K, assembled here element by element
  const Mesh3 mesh = box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1}, 0.3, 8);
  const AffineMap3 identity(mesh, kIdentity, {0, 0, 0});
  const P1Tet p1(mesh);
  const P2Tet p2(mesh);
  for (const Basis3* space : {static_cast<const Basis3*>(&p1), static_cast<const Basis3*>(&p2)}) {
    const int n = space->dof_count(), nd = space->local_dofs();
    std::vector<double> reference(static_cast<size_t>(n) * n, 0.0);
    std::vector<double> out(static_cast<size_t>(nd) * 4);
    std::vector<int> dofs(nd);
    for (int k = 0; k < mesh.size(); ++k) {
      Point3 p[4];
      mesh.corners(k, p);
      const double vol = volume6(p[0], p[1], p[2], p[3]) / 6;
      space->dofs(k, dofs.data());
      for (const RulePoint3& q : tetrahedron_rule(4)) {
        space->evaluate(k, q.xi, out.data());
        for (int i = 0; i < nd; ++i)
          for (int j = 0; j < nd; ++j) {
            const double* a = &out[4 * i];
            const double* b = &out[4 * j];
            reference[static_cast<size_t>(dofs[i]) * n + dofs[j]] +=
                vol * q.weight * (10 * a[0] * b[0] + (a[1] * b[1] + a[2] * b[2] + a[3] * b[3]));
          }
      }
    }
    const CsrMatrix b = couple(mesh, *space, mesh, *space, identity, 1, 10);
    double worst = 0, scale = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        worst = std::max(worst, std::fabs(b.at(i, j) - reference[static_cast<size_t>(i) * n + j]));
        scale = std::max(scale, std::fabs(reference[static_cast<size_t>(i) * n + j]));
      }
    EXPECT_LE(worst, 1e-13 * scale) << nd << " local dofs";
  }
}

TEST(Coupling3d, VectorSpacesChainAndListingGradients) {
  // [P1, P1, P1] on both sides, a rotated map: with the chain rule the three pairs give
  //   sum_c int grad L_c . A^T grad U_c (X(s)); with the listing order sum_{a,b} d_b L_a sum_c A_ac d_b U_c.
  const Mesh3 fluid = box_mesh(4, 4, 4, {-1, -1, -1}, {2, 2, 2}, 0.2, 12);
  const Mesh3 solid = box_mesh(2, 2, 2, {-0.3, -0.3, -0.3}, {0.6, 0.6, 0.6});
  double a[3][3];
  rotation({0, 1, 1}, 0.5, a);
  const AffineMap3 map(solid, a, {0.1, 0, 0});
  const VectorP1Tet fv(fluid), sv(solid);
  const Point3 gu[3] = {{0.3, -0.2, 0.5}, {1, 0.4, -0.6}, {-0.1, 0.7, 0.2}};  // U_c = gu[c] . y
  const Point3 gl[3] = {{0.2, 0.1, -0.4}, {-0.5, 0.3, 0.6}, {0.9, -0.2, 0.1}};  // L_a = gl[a] . s
  const int nvf = static_cast<int>(fluid.vertices.size()), nvs = static_cast<int>(solid.vertices.size());
  std::vector<double> uv(3 * nvf), lv(3 * nvs);
  for (int c = 0; c < 3; ++c) {
    for (int v = 0; v < nvf; ++v) uv[c * nvf + v] = dot(gu[c], fluid.vertices[v]);
    for (int v = 0; v < nvs; ++v) lv[c * nvs + v] = dot(gl[c], solid.vertices[v]);
  }
  const double volume = exact_volume(solid);
  double chain = 0, listing = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) chain += (&gl[c].x)[i] * a[j][i] * (&gu[c].x)[j];  // grad L_c . A^T grad U_c
  for (int aa = 0; aa < 3; ++aa)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c) listing += (&gl[aa].x)[b] * a[aa][c] * (&gu[c].x)[b];
  CouplingOptions opt;
  opt.c1 = 1;
  opt.c2 = 0;
  opt.fluid_components = {0, 1, 2};
  opt.solid_components = {0, 1, 2};
  const FluidSide3 fs(fluid, fv, opt.fluid_components);
  const SolidSide3 ss(solid, sv, opt.solid_components);
  EXPECT_NEAR(bilinear(assemble_coupling(fs, ss, map, opt), lv, uv), chain * volume, 1e-13 * std::fabs(chain * volume));
  opt.gradient = CouplingOptions::Gradient::Listing;
  EXPECT_NEAR(bilinear(assemble_coupling(fs, ss, map, opt), lv, uv), listing * volume, 1e-13 * std::fabs(listing * volume));
}

TEST(Coupling3d, ThreadsGiveTheSameMatrixBothMethods) {
  const Mesh3 fluid = box_mesh(4, 4, 4, {-1, -1, -1}, {2, 2, 2}, 0.2, 13);
  const Mesh3 solid = box_mesh(3, 3, 3, {-0.5, -0.5, -0.5}, {1, 1, 1}, 0.2, 14);
  double a[3][3];
  rotation({1, 0, 1}, 0.3, a);
  const AffineMap3 map(solid, a, {0, 0.05, 0});
  const P2Tet f(fluid);
  const P1Tet s(solid);
  for (auto method : {CouplingOptions::Method::Exact, CouplingOptions::Method::Quadrature}) {
    const CsrMatrix one = couple(fluid, f, solid, s, map, 1, 1, nullptr, 1, {0}, {0}, method);
    const CsrMatrix two = couple(fluid, f, solid, s, map, 1, 1, nullptr, 2, {0}, {0}, method);
    EXPECT_EQ(one.column, two.column);
    EXPECT_EQ(one.value, two.value);
  }
}

// An assembly kept across calls (a time loop: the map moves; then another fluid side, then another thread
// count) gives each call the matrix a fresh assembly gives, bit for bit: nothing kept leaks into the next.
TEST(Coupling3d, AKeptAssemblyGivesEachCallTheFreshMatrix) {
  const Mesh3 fluid = box_mesh(4, 4, 4, {-1, -1, -1}, {2, 2, 2}, 0.2, 13);
  const Mesh3 other_fluid = box_mesh(3, 4, 5, {-1, -1, -1}, {2, 2, 2}, 0.15, 17);
  const Mesh3 solid = box_mesh(3, 3, 3, {-0.5, -0.5, -0.5}, {1, 1, 1}, 0.2, 14);
  const P2Tet f(fluid), g(other_fluid);
  const P1Tet s(solid);
  const FluidSide3 fs(fluid, f, {0}), gs(other_fluid, g, {0});
  const SolidSide3 ss(solid, s, {0});
  for (auto method : {CouplingOptions::Method::Exact, CouplingOptions::Method::Quadrature}) {
    CouplingAssembly3 kept;
    int call = 0;
    for (const FluidSide3* side : {&fs, &fs, &gs, &gs})
      for (int threads : {1, 2}) {
        double a[3][3];
        rotation({1, 0, 1}, 0.3 + 0.01 * call++, a);
        const AffineMap3 map(solid, a, {0, 0.05, 0});
        CouplingOptions opt;
        opt.method = method;
        opt.threads = threads;
        const CsrMatrix& again = kept.assemble(*side, ss, map, opt);
        const CsrMatrix fresh = assemble_coupling(*side, ss, map, opt);
        EXPECT_EQ(again.start, fresh.start) << "call " << call;
        EXPECT_EQ(again.column, fresh.column) << "call " << call;
        EXPECT_EQ(again.value, fresh.value) << "call " << call;
      }
  }
}

// The quadrature method on data that is one polynomial over the whole fluid mesh (no kinks): its rule, of
// the product's degree, is exact, so it meets the same independent reference as the exact method; and on
// kinked (P1 interpolated) data it is close to the exact method but not equal (a quadrature error).
TEST(Coupling3dQuadrature, ExactOnGlobalPolynomialsUnderRotatedShearedMaps) {
  const Mesh3 fluid = box_mesh(5, 5, 5, {-1, -1, -1}, {2, 2, 2}, 0.25, 3);
  const Mesh3 solid = box_mesh(3, 2, 4, {-0.3, -0.3, -0.3}, {0.6, 0.6, 0.6}, 0.2, 4);
  double a[3][3];
  rotated_shear(a);
  const AffineMap3 map(solid, a, {0.05, -0.1, 0.07});
  const P2Tet fp2(fluid), sp2(solid);
  const P1Tet fp1(fluid);
  const std::vector<double> uv = interpolate(fp2, u2), lv = interpolate(sp2, l2);
  const FluidSide3 fs(fluid, fp2, {0});
  const SolidSide3 ss(solid, sp2, {0});
  for (int subdivide : {-1, 1, 2})
    for (double c1 : {0.0, 1.0}) {
      CouplingOptions opt;
      opt.method = CouplingOptions::Method::Quadrature;
      opt.c1 = c1;
      opt.subdivide = subdivide;
      CouplingReport report;
      const CsrMatrix b = assemble_coupling(fs, ss, map, opt, &report);
      const double exact = reference(solid, map, a, l2, gl2, u2, gu2, c1, 1);
      EXPECT_NEAR(bilinear(b, lv, uv), exact, 1e-13 * std::fabs(exact))
          << "subdivide " << subdivide << ", c1 = " << c1 << ": " << report.summary();
      EXPECT_EQ(report.outside_measure, 0);
    }
  // 1'B1 = the solid's volume (the weights in solid measure), whatever the map's det
  CouplingReport report;
  const CsrMatrix b = couple(fluid, fp1, solid, sp2, map, 0, 1, &report, 1, {0}, {0}, CouplingOptions::Method::Quadrature);
  double sum = 0;
  for (double v : b.value) sum += v;
  EXPECT_NEAR(sum, exact_volume(solid), 1e-13 * exact_volume(solid));
  // P1 fluid data interpolating u2 has kinks on the fluid faces: the rule is not exact there
  const std::vector<double> u1v = interpolate(fp1, u2);
  const CsrMatrix e = couple(fluid, fp1, solid, sp2, map, 0, 1);
  const double exact = bilinear(e, lv, u1v), quad = bilinear(b, lv, u1v);
  EXPECT_GT(std::fabs(quad - exact), 1e-9 * std::fabs(exact));
  EXPECT_LT(std::fabs(quad - exact), 1e-2 * std::fabs(exact));
}

// Rule points on the fluid's vertices, edges and faces (the walk's exact fallback decides): the centroid
// rule (qforder 0) on one solid tetrahedron whose centroid is the fluid box's middle vertex (0.5, 0.5, 0.5),
// shared by many fluid tetrahedra (to round-off: within the walk's margin), and the same under subdivide 1,
// one of whose parts' centroids, (0.45, 0.7, 0.5), lies on the fluid's grid plane z = 0.5. Data linear over
// the whole fluid: every tetrahedron holding a point gives the same value.
TEST(Coupling3dQuadrature, RulePointsOnFluidVerticesEdgesAndFaces) {
  const Mesh3 fluid = box_mesh(2, 2, 2, {0, 0, 0}, {1, 1, 1});
  Mesh3 solid;
  solid.vertices = {{0.1, 0.2, 0.3}, {0.9, 0.3, 0.4}, {0.4, 0.9, 0.5}, {0.6, 0.6, 0.8}};
  solid.tetrahedra = {{0, 1, 2, 3}};
  solid.build_adjacency();
  const P1Tet f(fluid), s(solid);
  const Field u = [](Point3 y) { return 0.5 - 0.2 * y.x + 0.9 * y.y + 0.6 * y.z; };
  const std::vector<double> uv = interpolate(f, u), lv(4, 1.0);
  const FluidSide3 fs(fluid, f, {0});
  const SolidSide3 ss(solid, s, {0});
  const AffineMap3 identity(solid, kIdentity, {0, 0, 0});
  Point3 c[4];
  solid.corners(0, c);
  const double volume = std::fabs(volume6(c[0], c[1], c[2], c[3])) / 6;
  for (int subdivide : {0, 1}) {
    CouplingOptions opt;
    opt.method = CouplingOptions::Method::Quadrature;
    opt.qforder = 0;
    opt.c1 = 0;
    opt.subdivide = subdivide;
    CouplingReport report;
    const double value = bilinear(assemble_coupling(fs, ss, identity, opt, &report), lv, uv);
    // the centroid rule is exact for linear data on each part, and the parts tile the tetrahedron
    EXPECT_NEAR(value, volume * u(0.25 * (c[0] + c[1] + c[2] + c[3])), 1e-14) << "subdivide " << subdivide;
    EXPECT_EQ(report.outside_measure, 0);
  }
}

TEST(Coupling3dQuadrature, PointsOutsideTheFluidAreAnErrorOrDropped) {
  const Mesh3 fluid = box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1}, 0.1, 5);
  const Mesh3 solid = box_mesh(2, 2, 2, {0.25, 0.25, 0.25}, {0.5, 0.5, 0.5}, 0.1, 6);
  const AffineMap3 out(solid, kIdentity, {0.5, 0, 0});  // half of the box beyond x = 1
  const P1Tet f(fluid), s(solid);
  CouplingOptions opt;
  opt.method = CouplingOptions::Method::Quadrature;
  const FluidSide3 fs(fluid, f, {0});
  const SolidSide3 ss(solid, s, {0});
  EXPECT_THROW(assemble_coupling(fs, ss, out, opt), Error);
  opt.drop_outside = true;
  CouplingReport report;
  assemble_coupling(fs, ss, out, opt, &report);
  EXPECT_GT(report.outside_measure, 0.2 * exact_volume(solid));
  EXPECT_LT(report.outside_measure, 0.8 * exact_volume(solid));
}

TEST(Coupling3d, BadInputIsAnError) {
  const Mesh3 fluid = box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1});
  const Mesh3 solid = box_mesh(2, 2, 2, {0.25, 0.25, 0.25}, {0.5, 0.5, 0.5});
  const P1Tet f(fluid), s(solid);
  auto message = [&](const SolidMap3& map, bool drop = false, CouplingReport* report = nullptr) {
    return coupling_error(fluid, solid, map, drop, report);
  };
  const double mirror[3][3] = {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_NE(message(AffineMap3(solid, mirror, {1, 0, 0})).find("inverts"), std::string::npos);
  const double flat[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  EXPECT_NE(message(AffineMap3(solid, flat, {0, 0, 0.5})).find("flattens"), std::string::npos);
  // moved by 0.5 along x: [0.75, 1.25] x ..., half of it outside the fluid box
  const AffineMap3 out(solid, kIdentity, {0.5, 0, 0});
  EXPECT_NE(message(out).find("leaves the fluid mesh"), std::string::npos);
  CouplingReport report;
  EXPECT_EQ(message(out, true, &report), "");
  EXPECT_NEAR(report.outside_measure, 0.0625, 1e-15);
  const double nan = std::nan("");
  const AffineMap3 bad(solid, kIdentity, {nan, 0, 0});
  EXPECT_NE(message(bad).find("NaN"), std::string::npos);
  CouplingOptions opt;
  opt.fluid_components = {0, 1};
  EXPECT_THROW(
      {
        const FluidSide3 fs(fluid, f, {0});
        const SolidSide3 ss(solid, s, {0});
        assemble_coupling(fs, ss, out, opt);
      },
      Error);
}

// A sliver whose volume (1e-306) lies below the normal doubles' products in either mesh is an error that names
// it; the mesh's other tetrahedra are of size 1 (scale.hpp's power-of-two scaling of a whole side does not help).
TEST(Coupling3d, TetrahedraOutsideTheSupportedSizesAreNamed) {
  // below the face (0, 0, 0), (1, 0, 0), (0, 1, 0) of the unit box, its fourth corner 1e-305 below that plane
  auto with_sliver = [](Mesh3 m) {
    const int n = static_cast<int>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, -1e-305}});
    m.tetrahedra.push_back({n, n + 2, n + 1, n + 3});
    m.build_adjacency();
    return m;
  };
  const Mesh3 fluid = with_sliver(box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1}));
  const P1Tet f(fluid);
  try {
    const FluidSide3 side(fluid, f, {0});
    ADD_FAILURE() << "no error for the fluid sliver";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("fluid tetrahedron " + std::to_string(fluid.size() - 1) + " is too small or too large"),
              std::string::npos)
        << message;
  }
  const Mesh3 box = box_mesh(3, 3, 3, {0, 0, 0}, {1, 1, 1});
  const Mesh3 solid = with_sliver(box_mesh(2, 2, 2, {0, 0, 0}, {1, 1, 1}));
  const AffineMap3 lifted(solid, kIdentity, {0, 0, 0.5});  // the sliver's image inside the fluid box
  const std::string message = coupling_error(box, solid, lifted, true);
  EXPECT_NE(message.find("solid tetrahedron " + std::to_string(solid.size() - 1) + " is too small or too large"),
            std::string::npos)
      << message;
}
