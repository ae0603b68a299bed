// Quadrature rules on the reference triangle {(0,0), (1,0), (0,1)}.
#pragma once
#include <vector>

#include "point.hpp"

namespace dlmfsi {

struct RulePoint {
  Point xi;       // reference coordinates
  double weight;  // weights sum to 1: the integral over a triangle of area A is A * sum(weight * f)
};

// A rule exact for polynomials of total degree <= degree (0 <= degree <= 60).
// Degrees 1, 2, 4, 5, 6 and 8 use the classical 1-, 3-, 6-, 7-, 12- and 16-point rules (centroid,
// Strang-Fix, Dunavant, Radon, Dunavant, Dunavant); the others a collapsed (Duffy) product of
// Gauss-Legendre rules,
//   int_T f = int_0^1 int_0^1 f(u, (1-u) v) (1-u) dv du,
// with ceil((degree+2)/2) points in u and ceil((degree+1)/2) in v. All weights are positive.
const std::vector<RulePoint>& triangle_rule(int degree);

// Gauss-Legendre nodes and weights on [0, 1], n points (exact for degree 2n-1).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace dlmfsi
