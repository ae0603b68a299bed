#include "solid/law.hpp"

#include <cmath>
#include <sstream>

#include "errors.hpp"

namespace dlmfsi {

namespace {

// Entry (i, j) of a gradient stored row by row.
inline double& at(Gradient2& m, int i, int j) { return m[2 * i + j]; }
inline double at(const Gradient2& m, int i, int j) { return m[2 * i + j]; }

double determinant(const Gradient2& f) { return f[0] * f[3] - f[1] * f[2]; }

// K = F^-T = cof(F) / J, J > 0 checked.
Gradient2 inverse_transpose(const Gradient2& f, double& j) {
  j = determinant(f);
  if (!(j > 0)) {
    std::ostringstream s;
    s << "law nh: J = det F = " << j << " <= 0 (the map folds or degenerates; the neo-Hookean law needs J > 0)";
    throw Error(s.str());
  }
  return {f[3] / j, -f[2] / j, -f[1] / j, f[0] / j};
}

// The law's state at Fl that DP(Fl)[H] needs: S(Fl) for svk, K and ln J for nh.
struct Linearization {
  SolidLaw law;
  LawConstants c;
  Gradient2 f{}, s{}, k{};
  double log_j = 0;

  Linearization(SolidLaw l, const LawConstants& constants, const Gradient2& fl) : law(l), c(constants), f(fl) {
    if (law == SolidLaw::Svk) {
      // E = (F'F - I)/2, S = lambda tr(E) I + 2 mu E
      const double e11 = (f[0] * f[0] + f[2] * f[2] - 1) / 2, e22 = (f[1] * f[1] + f[3] * f[3] - 1) / 2;
      const double e12 = (f[0] * f[1] + f[2] * f[3]) / 2;
      const double tr = e11 + e22;
      s = {c.lambda * tr + 2 * c.mu * e11, 2 * c.mu * e12, 2 * c.mu * e12, c.lambda * tr + 2 * c.mu * e22};
    } else if (law == SolidLaw::NeoHookean) {
      double j = 0;
      k = inverse_transpose(f, j);
      log_j = std::log(j);
    }
  }

  // DP(Fl)[H]
  Gradient2 derivative(const Gradient2& h) const {
    Gradient2 d{};
    if (law == SolidLaw::Listing) {
      // 2 mu sym H + lambda tr H I
      const double off = c.mu * (h[1] + h[2]), tr = c.lambda * (h[0] + h[3]);
      return {2 * c.mu * h[0] + tr, off, off, 2 * c.mu * h[3] + tr};
    }
    if (law == SolidLaw::Svk) {
      // H S + Fl (lambda tr Ed I + 2 mu Ed), Ed = sym(Fl' H)
      Gradient2 ed{};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          at(ed, i, j) = (at(f, 0, i) * at(h, 0, j) + at(f, 1, i) * at(h, 1, j) + at(f, 0, j) * at(h, 0, i) +
                          at(f, 1, j) * at(h, 1, i)) / 2;
      const double tr = ed[0] + ed[3];
      const Gradient2 ds = {c.lambda * tr + 2 * c.mu * ed[0], 2 * c.mu * ed[1], 2 * c.mu * ed[2],
                            c.lambda * tr + 2 * c.mu * ed[3]};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          at(d, i, j) = at(h, i, 0) * at(s, 0, j) + at(h, i, 1) * at(s, 1, j) + at(f, i, 0) * at(ds, 0, j) +
                        at(f, i, 1) * at(ds, 1, j);
      return d;
    }
    // mu H + (mu - lambda ln J) K H' K + lambda (K : H) K
    const double kh = k[0] * h[0] + k[1] * h[1] + k[2] * h[2] + k[3] * h[3];
    const double a = c.mu - c.lambda * log_j;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        double khk = 0;
        for (int p = 0; p < 2; ++p)
          for (int q = 0; q < 2; ++q) khk += at(k, i, p) * at(h, q, p) * at(k, q, j);
        at(d, i, j) = c.mu * at(h, i, j) + a * khk + c.lambda * kh * at(k, i, j);
      }
    return d;
  }
};

}  // namespace

SolidLaw solid_law(const std::string& name) {
  if (name == "listing") return SolidLaw::Listing;
  if (name == "svk") return SolidLaw::Svk;
  if (name == "nh") return SolidLaw::NeoHookean;
  throw Error("law=\"" + name + "\": expected \"listing\", \"svk\" or \"nh\"");
}

const char* solid_law_name(SolidLaw law) {
  return law == SolidLaw::Listing ? "listing" : (law == SolidLaw::Svk ? "svk" : "nh");
}

Gradient2 first_piola(SolidLaw law, const LawConstants& c, const Gradient2& f) {
  if (law == SolidLaw::Listing) {
    // 2 mu sym(F - I) + lambda tr(F - I) I
    const double tr = c.lambda * (f[0] + f[3] - 2), off = c.mu * (f[1] + f[2]);
    return {2 * c.mu * (f[0] - 1) + tr, off, off, 2 * c.mu * (f[3] - 1) + tr};
  }
  const Linearization at_f(law, c, f);
  Gradient2 p{};
  if (law == SolidLaw::Svk) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) at(p, i, j) = at(f, i, 0) * at(at_f.s, 0, j) + at(f, i, 1) * at(at_f.s, 1, j);
    return p;
  }
  for (int e = 0; e < 4; ++e) p[e] = c.mu * (f[e] - at_f.k[e]) + c.lambda * at_f.log_j * at_f.k[e];
  return p;
}

Gradient2 stress_derivative(SolidLaw law, const LawConstants& c, const Gradient2& f, const Gradient2& h) {
  return Linearization(law, c, f).derivative(h);
}

void tangent(SolidLaw law, const LawConstants& c, const Gradient2& fl, double t[16]) {
  const Linearization at_fl(law, c, fl);
  for (int j = 0; j < 4; ++j) {
    Gradient2 unit{};
    unit[j] = 1;
    const Gradient2 d = at_fl.derivative(unit);
    for (int i = 0; i < 4; ++i) t[4 * i + j] = d[i];
  }
}

Gradient2 linearization_stress(SolidLaw law, const LawConstants& c, const Gradient2& fl) {
  if (law == SolidLaw::Listing) {
    const double d = 2 * (c.mu + c.lambda);
    return {d, 0, 0, d};
  }
  if (law == SolidLaw::Svk) {
    // Fl (lambda tr C I + 2 mu C), C = Fl' Fl
    const double c11 = fl[0] * fl[0] + fl[2] * fl[2], c22 = fl[1] * fl[1] + fl[3] * fl[3];
    const double c12 = fl[0] * fl[1] + fl[2] * fl[3];
    const double tr = c.lambda * (c11 + c22);
    const Gradient2 m = {tr + 2 * c.mu * c11, 2 * c.mu * c12, 2 * c.mu * c12, tr + 2 * c.mu * c22};
    Gradient2 r{};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) at(r, i, j) = at(fl, i, 0) * at(m, 0, j) + at(fl, i, 1) * at(m, 1, j);
    return r;
  }
  double j = 0;
  const Gradient2 k = inverse_transpose(fl, j);
  const double a = 2 * (c.mu + c.lambda - c.lambda * std::log(j));
  return {a * k[0], a * k[1], a * k[2], a * k[3]};
}

}  // namespace dlmfsi
