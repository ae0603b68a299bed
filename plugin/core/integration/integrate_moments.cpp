#include "integration/integrate_moments.hpp"

#include "sides/report.hpp"
#include "sides/sides.hpp"

namespace dlmfsi {

// Area, centroid and central second moments M = int_P (y - c)(y - c)^T dy of a convex piece, from its fan
// in coordinates relative to the first corner: the triangle (0, p, q) of area a = (p x q) / 2 has
// int y = a (p + q) / 3 and int y y^T = a/6 (p p^T + q q^T + (p q^T + q p^T)/2). The fan's sums are taken
// with the factors 1/6, 1/12 and 1/24 left out, and divided once at the end.
struct MomentIntegrator::Moments {
  double area = 0;
  Point centroid;
  double mxx = 0, mxy = 0, myy = 0;

  explicit Moments(const Piece& piece) {
    const Point o = piece.v[0];
    // twice the area; 6 int y; 12 int x^2, 12 int y^2; 24 int x y
    double a2 = 0, cx = 0, cy = 0, sxx = 0, sxy = 0, syy = 0;
    for (int t = 1; t + 1 < piece.n; ++t) {
      const Point p = piece.v[t] - o, q = piece.v[t + 1] - o;
      const double c = cross(p, q);
      a2 += c;
      cx += c * (p.x + q.x);
      cy += c * (p.y + q.y);
      sxx += c * (p.x * p.x + q.x * q.x + p.x * q.x);
      syy += c * (p.y * p.y + q.y * q.y + p.y * q.y);
      sxy += c * (2 * p.x * p.y + 2 * q.x * q.y + p.x * q.y + q.x * p.y);
    }
    area = 0.5 * a2;
    if (!(area > 0)) return;
    cx /= 3 * a2;  // the centroid relative to o: (6 int y) / (6 area)
    cy /= 3 * a2;
    mxx = sxx / 12 - area * cx * cx;  // about the centroid
    myy = syy / 12 - area * cy * cy;
    mxy = sxy / 24 - area * cx * cy;
    centroid = {o.x + cx, o.y + cy};
  }
};

namespace {

// PolynomialBasis::evaluate_affine for three functions of three monomials (1, xi1, xi2) each.
inline void affine3(const PolynomialBasis& basis, int k, Point xi, double* value, double* dx, double* dy) {
  const double* c = basis.coefficients(k);
  const double* j = basis.inverse_jacobian(k);
  for (int f = 0; f < 3; ++f, c += 3) {
    value[f] = c[0] + c[1] * xi.x + c[2] * xi.y;
    dx[f] = c[1] * j[0] + c[2] * j[2];
    dy[f] = c[1] * j[1] + c[2] * j[3];
  }
}

// PolynomialBasis::evaluate_affine's values alone, for `width` functions of three monomials (1, xi1, xi2)
// each (W = 3: unrolled) or of one monomial (1).
template <int W>
inline void affine_values(const PolynomialBasis& basis, int k, Point xi, int width, double* value) {
  const double* c = basis.coefficients(k);
  if (!W && basis.terms() == 1) {
    for (int f = 0; f < width; ++f) value[f] = c[f];
    return;
  }
  for (int f = 0; f < (W ? W : width); ++f, c += 3) value[f] = c[0] + c[1] * xi.x + c[2] * xi.y;
}

}  // namespace

bool MomentIntegrator::applies(const Integrand& integrand) {
  const PolynomialBasis &fluid = integrand.fluid, &multiplier = integrand.multiplier;
  return fluid.fitted() && multiplier.fitted() && fluid.degree() <= 1 && multiplier.degree() <= 1 &&
         fluid.functions().size() <= static_cast<size_t>(kMaxFunctions) &&
         multiplier.functions().size() <= static_cast<size_t>(kMaxFunctions);
}

MomentIntegrator::MomentIntegrator(const Integrand& integrand, CouplingReport& counts)
    : integrand_(integrand), counts_(counts), gradients_(integrand.c1 != 0),
      fluid_functions_(static_cast<int>(integrand.fluid.functions().size())),
      multiplier_functions_(static_cast<int>(integrand.multiplier.functions().size())) {
  const ComponentPairs& pairs = integrand.pairs;
  auto in_order = [](const std::vector<int>& functions, int count) {
    if (static_cast<int>(functions.size()) != count) return false;
    for (int f = 0; f < count; ++f)
      if (functions[f] != f) return false;
    return true;
  };
  one_pair_ = pairs.size() == 1 && in_order(pairs[0].fluid_functions, fluid_functions_) &&
              in_order(pairs[0].solid_functions, multiplier_functions_);
  if (fluid_functions_ == 3 && multiplier_functions_ == 3 && integrand.fluid.terms() == 3 &&
      integrand.multiplier.terms() == 3)
    add_ = &MomentIntegrator::add<3, 3>;
  else
    add_ = &MomentIntegrator::add<0, 0>;
}

void MomentIntegrator::start(const ClippedImage& image) {
  const MappedTriangle& mt = image.triangle;
  const double(&j)[2][2] = mt.affine_value.jac;  // dX_a/ds_b
  const double det = mt.affine_det;
  mass_ = integrand_.c2 / det;
  // the gradients in s (a fit of degree <= 1: the same at every point), as evaluate_affine forms them, and
  // in y: (dX/ds)^-T grad_s psi
  auto in_y = [&](double gx, double gy, int f) {
    sgx_[f] = gx;
    sgy_[f] = gy;
    syx_[f] = (j[1][1] * gx - j[1][0] * gy) / det;
    syy_[f] = (j[0][0] * gy - j[0][1] * gx) / det;
  };
  if (add_ == &MomentIntegrator::add<3, 3>) {  // three functions of 1, xi1, xi2
    const double* c = integrand_.multiplier.coefficients(mt.k);
    const double* jinv = integrand_.multiplier.inverse_jacobian(mt.k);
    double gx[3], gy[3];
    for (int f = 0; f < 3; ++f) {
      gx[f] = c[3 * f + 1] * jinv[0] + c[3 * f + 2] * jinv[2];
      gy[f] = c[3 * f + 1] * jinv[1] + c[3 * f + 2] * jinv[3];
    }
    for (int f = 0; f < 3; ++f) in_y(gx[f], gy[f], f);
    return;
  }
  double values[kMaxFunctions], gx[kMaxFunctions], gy[kMaxFunctions];
  integrand_.multiplier.evaluate_affine(mt.k, Point{}, values, gx, gy);
  for (int f = 0; f < multiplier_functions_; ++f) in_y(gx[f], gy[f], f);
}

double MomentIntegrator::integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) {
  const Moments moments(piece);  // its area is piece.area(): the same fan, the same products and sums
  counts_.points += 1;
  if (moments.area > 0) (this->*add_)(image, kf, moments, block);  // else a piece of round-off size
  return moments.area;
}

template <int FW, int SW>
void MomentIntegrator::add(const ClippedImage& image, int kf, const Moments& mo, LocalBlock& block) {
  const MappedTriangle& mt = image.triangle;
  const int fw = FW ? FW : fluid_functions_, sw = SW ? SW : multiplier_functions_;
  const PolynomialBasis &fluid = integrand_.fluid, &multiplier = integrand_.multiplier;
  // the centroid relative to image.origin, as the piece
  const Point eta = fluid.to_reference(kf, mo.centroid, image.origin), xi = image.pull_back(mo.centroid);
  double fv[kMaxFunctions], fgx[kMaxFunctions], fgy[kMaxFunctions], sv[kMaxFunctions];
  if (FW == 3 && SW == 3)  // three functions of 1, xi1, xi2 each (P1): evaluate_affine's sums, unrolled
    affine3(fluid, kf, eta, fv, fgx, fgy);
  else
    fluid.evaluate_affine(kf, eta, fv, fgx, fgy);
  affine_values<SW>(multiplier, mt.k, xi, sw, sv);
  const double *sgx = sgx_, *sgy = sgy_, *syx = syx_, *syy = syy_;  // start()'s
  const double(&j)[2][2] = mt.affine_value.jac;  // dX_a/ds_b
  const double area = mo.area, mass = mass_;
  // per fluid function: c2/det (A phi(c), M grad phi), and the chain-rule gradient times c1 A / det
  double fa[kMaxFunctions], fmx[kMaxFunctions], fmy[kMaxFunctions], fcx[kMaxFunctions], fcy[kMaxFunctions];
  for (int f = 0; f < fw; ++f) {
    fa[f] = mass * area * fv[f];
    fmx[f] = mass * (mo.mxx * fgx[f] + mo.mxy * fgy[f]);
    fmy[f] = mass * (mo.mxy * fgx[f] + mo.myy * fgy[f]);
  }
  if (gradients_) {
    const double stiff = integrand_.c1 * area / mt.affine_det;
    for (int f = 0; f < fw; ++f) {
      fcx[f] = stiff * (fgx[f] * j[0][0] + fgy[f] * j[1][0]);
      fcy[f] = stiff * (fgx[f] * j[0][1] + fgy[f] * j[1][1]);
    }
  }
  auto entry = [&](int f, int g) {
    double sum = fa[f] * sv[g] + fmx[f] * syx[g] + fmy[f] * syy[g];
    if (gradients_) sum += fcx[f] * sgx[g] + fcy[f] * sgy[g];
    return sum;
  };
  const ComponentPairs& pairs = integrand_.pairs;
  if (one_pair_) {
    const ComponentPair& pair = pairs[0];
    for (int f = 0; f < fw; ++f) {
      double* column = block.column(pair.fluid_first + f) + pair.solid_first;
      for (int g = 0; g < sw; ++g) column[g] += entry(f, g);
    }
    return;
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      double* column = block.column(pair.fluid_first + static_cast<int>(a)) + pair.solid_first;
      for (size_t b = 0; b < pair.solid_functions.size(); ++b)
        column[b] += entry(pair.fluid_functions[a], pair.solid_functions[b]);
    }
  }
}

}  // namespace dlmfsi
