#include "integrate_moments.hpp"

#include "coupling.hpp"

namespace dlmfsi {

bool MomentIntegrator::applies(const Integrand& integrand) {
  const PolynomialBasis &fluid = integrand.fluid, &multiplier = integrand.multiplier;
  return fluid.fitted() && multiplier.fitted() && fluid.degree() <= 1 && multiplier.degree() <= 1 &&
         fluid.functions().size() <= static_cast<size_t>(kMaxFunctions) &&
         multiplier.functions().size() <= static_cast<size_t>(kMaxFunctions);
}

MomentIntegrator::MomentIntegrator(const Integrand& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), gradients_(integrand.c1 != 0),
      fluid_functions_(static_cast<int>(integrand.fluid.functions().size())),
      multiplier_functions_(static_cast<int>(integrand.multiplier.functions().size())) {}

namespace {

// Area, centroid and central second moments M = int_P (y - c)(y - c)^T dy of a convex piece, from its fan
// in coordinates relative to the first corner: the triangle (0, p, q) of area a has int y = a (p + q) / 3
// and int y y^T = a/6 (p p^T + q q^T + (p q^T + q p^T)/2).
struct Moments {
  double area = 0;
  Point centroid;
  double mxx = 0, mxy = 0, myy = 0;
};

Moments moments(const Piece& piece) {
  const Point o = piece.v[0];
  double area = 0, cx = 0, cy = 0, mxx = 0, mxy = 0, myy = 0;
  for (int t = 1; t + 1 < piece.n; ++t) {
    const Point p = piece.v[t] - o, q = piece.v[t + 1] - o;
    const double a = 0.5 * cross(p, q);
    area += a;
    cx += a * (p.x + q.x) / 3;
    cy += a * (p.y + q.y) / 3;
    mxx += a / 6 * (p.x * p.x + q.x * q.x + p.x * q.x);
    myy += a / 6 * (p.y * p.y + q.y * q.y + p.y * q.y);
    mxy += a / 12 * (2 * p.x * p.y + 2 * q.x * q.y + p.x * q.y + q.x * p.y);
  }
  Moments m;
  m.area = area;
  if (!(area > 0)) return m;
  cx /= area;
  cy /= area;
  m.mxx = mxx - area * cx * cx;  // about the centroid
  m.myy = myy - area * cy * cy;
  m.mxy = mxy - area * cx * cy;
  m.centroid = {o.x + cx, o.y + cy};
  return m;
}

}  // namespace

void MomentIntegrator::integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) {
  const MappedTriangle& mt = image.triangle;
  const Moments mo = moments(piece);
  counts_.points += 1;
  if (!(mo.area > 0)) return;  // a piece of round-off size: nothing to add
  const double area = mo.area, mxx = mo.mxx, mxy = mo.mxy, myy = mo.myy;
  const Point c = mo.centroid;
  const PolynomialBasis &fluid = integrand_.fluid, &multiplier = integrand_.multiplier;
  const Point eta = fluid.to_reference(kf, c), xi = mt.affine_reference(c);
  double fv[kMaxFunctions], fgx[kMaxFunctions], fgy[kMaxFunctions];
  double sv[kMaxFunctions], sgx[kMaxFunctions], sgy[kMaxFunctions];
  fluid.evaluate_affine(kf, eta, fv, fgx, fgy);
  multiplier.evaluate_affine(mt.k, xi, sv, sgx, sgy);
  const double(&j)[2][2] = mt.affine_value.jac;  // dX_a/ds_b
  const double det = mt.affine_det, mass = integrand_.c2 / det, stiff = integrand_.c1 * area / det;
  // per fluid function: c2/det (A phi(c), M grad phi), and the chain-rule gradient times c1 A / det
  double fa[kMaxFunctions], fmx[kMaxFunctions], fmy[kMaxFunctions], fcx[kMaxFunctions], fcy[kMaxFunctions];
  for (int f = 0; f < fluid_functions_; ++f) {
    fa[f] = mass * area * fv[f];
    fmx[f] = mass * (mxx * fgx[f] + mxy * fgy[f]);
    fmy[f] = mass * (mxy * fgx[f] + myy * fgy[f]);
    fcx[f] = stiff * (fgx[f] * j[0][0] + fgy[f] * j[1][0]);
    fcy[f] = stiff * (fgx[f] * j[0][1] + fgy[f] * j[1][1]);
  }
  // per multiplier function: its gradient in y, (dX/ds)^-T grad_s psi
  double syx[kMaxFunctions], syy[kMaxFunctions];
  for (int f = 0; f < multiplier_functions_; ++f) {
    syx[f] = (j[1][1] * sgx[f] - j[1][0] * sgy[f]) / det;
    syy[f] = (j[0][0] * sgy[f] - j[0][1] * sgx[f]) / det;
  }
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      const int f = pair.fluid_functions[a];
      double* column = block.column(pair.fluid_first + static_cast<int>(a)) + pair.solid_first;
      for (size_t b = 0; b < pair.solid_functions.size(); ++b) {
        const int g = pair.solid_functions[b];
        double sum = fa[f] * sv[g] + fmx[f] * syx[g] + fmy[f] * syy[g];
        if (gradients_) sum += fcx[f] * sgx[g] + fcy[f] * sgy[g];
        column[b] += sum;
      }
    }
  }
}

}  // namespace dlmfsi
