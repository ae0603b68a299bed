// The solid's elastic laws, point by point: the first Piola stress P(F), its derivative DP(F)[H] and the two
// pieces of a Newton step about a linearization gradient Fl (edp/lib/solid.idp states the scheme):
//   the tangent    DP(Fl)[H] : G           (the matrix, bilinear in the unknown's H and the test's G),
//   the stress     DP(Fl)[Fl] - P(Fl)      (the right-hand side, against G),
// so that P(F) ~ P(Fl) + DP(Fl)[F - Fl] = DP(Fl)[F] - (DP(Fl)[Fl] - P(Fl)). Lame constants lambda, mu;
// the same small-strain limit 2 mu eps + lambda tr(eps) I for the three laws:
//   listing: P = 2 mu sym(F - I) + lambda tr(F - I) I (linear in F, not frame invariant);
//   svk    : St Venant-Kirchhoff, E = (F'F - I)/2, S = lambda tr(E) I + 2 mu E, P = F S;
//   nh     : compressible neo-Hookean, P = mu (F - K) + lambda ln(J) K, J = det F, K = F^-T (J > 0).
// A gradient is the 2x2 matrix F_ij = d x_i / d X_j stored row by row: (F11, F12, F21, F22).
#pragma once
#include <array>
#include <string>

namespace dlmfsi {

using Gradient2 = std::array<double, 4>;

enum class SolidLaw { Listing, Svk, NeoHookean };

// "listing", "svk" or "nh"; any other name is an Error naming it.
SolidLaw solid_law(const std::string& name);
const char* solid_law_name(SolidLaw law);

struct LawConstants {
  double lambda = 0, mu = 0;
};

// P(F). nh: an Error when J = det F <= 0.
Gradient2 first_piola(SolidLaw law, const LawConstants& c, const Gradient2& f);

// DP(F)[H]. nh: an Error when J <= 0.
Gradient2 stress_derivative(SolidLaw law, const LawConstants& c, const Gradient2& f, const Gradient2& h);

// The tangent as a 4x4 matrix over the gradient entries: t[4 i + j] = DP(Fl)[E_j] : E_i (E_j the unit
// gradient of entry j), so that DP(Fl)[H] : G = sum_ij G_i t[4 i + j] H_j. Symmetric (the three laws derive
// from an energy). Closed forms, with Ed(H) = sym(Fl' H), S = S(Fl), K = Fl^-T:
//   listing: 2 mu sym H : sym G + lambda tr H tr G;
//   svk    : S : (H' G) + lambda tr Ed(H) tr Ed(G) + 2 mu Ed(H) : Ed(G);
//   nh     : mu H : G + (mu - lambda ln J) (K H' K) : G + lambda (K : H)(K : G).
// nh: an Error when J <= 0.
void tangent(SolidLaw law, const LawConstants& c, const Gradient2& fl, double t[16]);

// DP(Fl)[Fl] - P(Fl) in closed form:
//   listing: 2 (mu + lambda) I;   svk: Fl (lambda tr C I + 2 mu C), C = Fl' Fl;
//   nh: 2 (mu + lambda - lambda ln J) K.
// nh: an Error when J <= 0.
Gradient2 linearization_stress(SolidLaw law, const LawConstants& c, const Gradient2& fl);

}  // namespace dlmfsi
