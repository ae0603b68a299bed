#include "integration/integrate_moments3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "sides/report.hpp"
#include "sides/sides3d.hpp"

namespace dlmfsi {

namespace {

// Volume, centroid and central second moments M = int_P (y - c)(y - c)^T dy of a piece, from its
// tetrahedra: with vertices 0, a, b, c relative to the piece's apex, a tetrahedron of volume V has
// int y = V (a + b + c) / 4 and int y y^T = V / 20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
// The vectors are taken in units of 2^e, about the piece's size (scale: 2^e, scaling exact), so that the
// first and second moments are V times numbers near 1 (in the caller's units they would be V h and V h^2:
// outside the doubles for pieces beyond about 1e-60..1e60 in size); m holds M / 2^(2 e).
struct Moments {
  double volume = 0;
  Point3 centroid;
  double scale = 1;
  double m[3][3] = {};
};

// e with x = f 2^e, 0.5 <= f < 1 (std::frexp's), for a finite x > 0: from the exponent field when x is
// normal (field - 1022), else by frexp (a libm call, about 140 instructions: here once per piece).
inline int frexp_exponent(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int field = static_cast<int>(bits >> 52) & 0x7FF;
  if (field != 0) return field - 1022;
  int e = 0;
  std::frexp(x, &e);
  return e;
}

// 2^e, exactly std::ldexp(1.0, e): from the exponent field where 2^e is a normal double.
inline double power_of_two(int e) {
  if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
  const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023) << 52;
  double out;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

Moments moments(const Piece3& piece) {
  Moments out;
  const int apex = piece.apex();  // the triangulation's: every tetrahedron's first corner
  const Point3 o = piece.v[apex];
  double size = 0;
  for (int k = 0; k < piece.n; ++k) {
    const Point3 d = piece.v[k] - o;
    size = std::max({size, std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  }
  int e = 0;
  if (size > 0 && std::isfinite(size)) e = frexp_exponent(size);
  out.scale = power_of_two(e);
  const double shrink = power_of_two(-e);
  // Over the tetrahedra (apex, a, b, c) of the pulling triangulation from the apex: volume v, int y = v s / 4
  // and int y y^T = v / 20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c (the shrunk points), upper triangle.
  double volume = 0, f0 = 0, f1 = 0, f2 = 0, m00 = 0, m01 = 0, m02 = 0, m11 = 0, m12 = 0, m22 = 0;
  piece.for_each_tetrahedron_from(apex, [&](int, int ip, int iq, int ir) {
    const Point3 a = piece.v[ip] - o, b = piece.v[iq] - o, c = piece.v[ir] - o;
    const double v = std::fabs(dot(a, cross(b, c))) / 6;
    volume += v;
    const Point3 as = shrink * a, bs = shrink * b, cs = shrink * c, t = as + bs + cs;
    f0 += v * t.x / 4;
    f1 += v * t.y / 4;
    f2 += v * t.z / 4;
    const double w = v / 20;
    m00 += w * (as.x * as.x + bs.x * bs.x + cs.x * cs.x + t.x * t.x);
    m01 += w * (as.x * as.y + bs.x * bs.y + cs.x * cs.y + t.x * t.y);
    m02 += w * (as.x * as.z + bs.x * bs.z + cs.x * cs.z + t.x * t.z);
    m11 += w * (as.y * as.y + bs.y * bs.y + cs.y * cs.y + t.y * t.y);
    m12 += w * (as.y * as.z + bs.y * bs.z + cs.y * cs.z + t.y * t.z);
    m22 += w * (as.z * as.z + bs.z * bs.z + cs.z * cs.z + t.z * t.z);
  });
  out.volume = volume;
  const double first[3] = {f0, f1, f2};
  const double second[3][3] = {{m00, m01, m02}, {m01, m11, m12}, {m02, m12, m22}};
  if (!(out.volume > 0)) return out;
  const double c[3] = {first[0] / out.volume, first[1] / out.volume, first[2] / out.volume};
  out.centroid = o + out.scale * Point3{c[0], c[1], c[2]};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.m[i][j] = second[i][j] - out.volume * c[i] * c[j];
  return out;
}

}  // namespace

void MomentIntegrator3::start(const ClippedImage3& image) {
  const MappedTet& mt = image.tetrahedron;
  const double(&j)[3][3] = mt.affine_value.jac;
  SolidTerms& st = solid_terms_;
  // the gradients in s (degree <= 1: the same at every point, here the reference origin's); the values there
  // are not kept
  double values[kMaxFunctions];
  integrand_.multiplier.evaluate_affine(mt.k, Point3{}, values, st.gradient_s);
  const double* sg = st.gradient_s;
  const double det = mt.affine_det;
  st.mass = integrand_.c2 / det;
  const double cof[3][3] = {{j[1][1] * j[2][2] - j[1][2] * j[2][1], j[1][2] * j[2][0] - j[1][0] * j[2][2], j[1][0] * j[2][1] - j[1][1] * j[2][0]},
                            {j[0][2] * j[2][1] - j[0][1] * j[2][2], j[0][0] * j[2][2] - j[0][2] * j[2][0], j[0][1] * j[2][0] - j[0][0] * j[2][1]},
                            {j[0][1] * j[1][2] - j[0][2] * j[1][1], j[0][2] * j[1][0] - j[0][0] * j[1][2], j[0][0] * j[1][1] - j[0][1] * j[1][0]}};
  for (int f = 0; f < multiplier_functions_; ++f)
    for (int a = 0; a < 3; ++a)  // (J^-T g)_a = sum_b (J^-1)_ba g_b, J^-1 = cof^T / det
      st.gradient_y[3 * f + a] = (cof[a][0] * sg[3 * f] + cof[a][1] * sg[3 * f + 1] + cof[a][2] * sg[3 * f + 2]) / det;
}

bool MomentIntegrator3::applies(const Integrand3& integrand) {
  const PolynomialBasis3 &fluid = integrand.fluid, &multiplier = integrand.multiplier;
  return fluid.fitted() && multiplier.fitted() && fluid.degree() <= 1 && multiplier.degree() <= 1 &&
         (integrand.chain || integrand.c1 == 0) && static_cast<int>(fluid.functions().size()) <= kMaxFunctions &&
         static_cast<int>(multiplier.functions().size()) <= kMaxFunctions;
}

MomentIntegrator3::MomentIntegrator3(const Integrand3& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), fluid_functions_(static_cast<int>(integrand.fluid.functions().size())),
      multiplier_functions_(static_cast<int>(integrand.multiplier.functions().size())) {
  const std::vector<int> in_order = {0, 1, 2, 3};
  const ComponentPairs& pairs = integrand.pairs;
  scalar_p1_mass_ = integrand.c1 == 0 && fluid_functions_ == 4 && multiplier_functions_ == 4 && pairs.size() == 1 &&
                    pairs[0].fluid_functions == in_order && pairs[0].solid_functions == in_order;
}

double MomentIntegrator3::add_scalar_p1_mass(double volume, const double (&m)[3][3], double scale, const double* fv,
                                             const double* fg, const double* sv, LocalBlock& block) {
  const SolidTerms& st = solid_terms_;
  const double mass = st.mass;
  double sy[12];
  for (int f = 0; f < 12; ++f) sy[f] = st.gradient_y[f] * scale;
  const ComponentPair& pair = integrand_.pairs[0];
  for (int a = 0; a < 4; ++a) {
    const double* g = fg + 3 * a;
    const double va = mass * volume * fv[a];
    const double m0 = mass * (m[0][0] * g[0] + m[0][1] * g[1] + m[0][2] * g[2]) * scale;
    const double m1 = mass * (m[1][0] * g[0] + m[1][1] * g[1] + m[1][2] * g[2]) * scale;
    const double m2 = mass * (m[2][0] * g[0] + m[2][1] * g[1] + m[2][2] * g[2]) * scale;
    double* col = block.column(pair.fluid_first + a) + pair.solid_first;
    for (int b = 0; b < 4; ++b) col[b] += va * sv[b] + m0 * sy[3 * b] + m1 * sy[3 * b + 1] + m2 * sy[3 * b + 2];
  }
  return volume;
}

double MomentIntegrator3::integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) {
  const MappedTet& mt = image.tetrahedron;
  const Moments mo = moments(piece);
  counts_.points += 1;
  if (!(mo.volume > 0)) return mo.volume;
  double fv[kMaxFunctions], fg[3 * kMaxFunctions], sv[kMaxFunctions];
  // the centroid relative to image.origin, as the piece
  integrand_.fluid.evaluate_affine(kf, integrand_.fluid.to_reference(kf, mo.centroid, image.origin), fv, fg);
  const Point3 xi = mt.affine_reference(mo.centroid, image.origin);
  const SolidTerms& st = solid_terms_;  // start()'s
  const double* sg = st.gradient_s;
  // the multiplier's values at the centroid (its gradients are kept per tetrahedron)
  integrand_.multiplier.values_affine(mt.k, xi, sv);
  if (scalar_p1_mass_) return add_scalar_p1_mass(mo.volume, mo.m, mo.scale, fv, fg, sv, block);
  const double(&j)[3][3] = mt.affine_value.jac;
  const double det = mt.affine_det, stiff = integrand_.c1 * mo.volume / det;
  const double mass = st.mass;
  // per multiplier function: its gradient in y times 2^e
  double sy[3 * kMaxFunctions];
  for (int f = 0; f < 3 * multiplier_functions_; ++f) sy[f] = st.gradient_y[f] * mo.scale;
  // per fluid function: c2/det (V phi(c), M grad phi / 2^e) and c1 V / det J^T grad phi (the 2^e of the moments'
  // units cancel in the products with sy, each factor a double at any size)
  double fa[kMaxFunctions], fm[3 * kMaxFunctions], fc[3 * kMaxFunctions];
  const bool gradients = integrand_.c1 != 0;
  for (int f = 0; f < fluid_functions_; ++f) {
    const double* g = fg + 3 * f;
    fa[f] = mass * mo.volume * fv[f];
    for (int a = 0; a < 3; ++a) fm[3 * f + a] = mass * (mo.m[a][0] * g[0] + mo.m[a][1] * g[1] + mo.m[a][2] * g[2]) * mo.scale;
    if (gradients)
      for (int a = 0; a < 3; ++a) fc[3 * f + a] = stiff * (g[0] * j[0][a] + g[1] * j[1][a] + g[2] * j[2][a]);
  }
  const ComponentPairs& pairs = integrand_.pairs;
  const size_t pair_count = pairs.size();
  for (size_t p = 0; p < pair_count; ++p) {
    const ComponentPair& pair = pairs[p];
    const int *fluid = pair.fluid_functions.data(), *solid = pair.solid_functions.data();
    const int nf = static_cast<int>(pair.fluid_functions.size()), ns = static_cast<int>(pair.solid_functions.size());
    // the pair's solid functions' value and gradient terms in column order, gathered once for its nf columns
    double s0[kMaxFunctions], s1[kMaxFunctions], s2[kMaxFunctions], s3[kMaxFunctions];
    for (int b = 0; b < ns; ++b) {
      const int g = solid[b];
      s0[b] = sv[g];
      s1[b] = sy[3 * g];
      s2[b] = sy[3 * g + 1];
      s3[b] = sy[3 * g + 2];
    }
    for (int a = 0; a < nf; ++a) {
      const int f = fluid[a];
      const double va = fa[f], m0 = fm[3 * f], m1 = fm[3 * f + 1], m2 = fm[3 * f + 2];
      double* col = block.column(pair.fluid_first + a) + pair.solid_first;
      if (gradients) {
        for (int b = 0; b < ns; ++b) {
          const int g = solid[b];
          const double sum = va * s0[b] + m0 * s1[b] + m1 * s2[b] + m2 * s3[b];
          col[b] += sum + (fc[3 * f] * sg[3 * g] + fc[3 * f + 1] * sg[3 * g + 1] + fc[3 * f + 2] * sg[3 * g + 2]);
        }
      } else {
        for (int b = 0; b < ns; ++b) col[b] += va * s0[b] + m0 * s1[b] + m1 * s2[b] + m2 * s3[b];
      }
    }
  }
  return mo.volume;
}

}  // namespace dlmfsi
