// Quadrature rules on the reference triangle {(0,0), (1,0), (0,1)}.
#pragma once
#include <vector>

#include "point.hpp"
#include "point3.hpp"

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
// The same for integrands that are polynomials of degree <= degree, with fewer points: degrees 10, 12, 14, 16, 18
// and 20 (and the odd ones below them) fully symmetric rules of 25, 33, 42, 55, 67 and 79 points solved for this
// project, the others triangle_rule's. On a smooth integrand that is not a polynomial, triangle_rule's products
// leave less of its remainder (a 2D P1b map at degree 10: 4.2e-14 against 2.1e-13).
const std::vector<RulePoint>& triangle_rule_for_polynomials(int degree);

// Gauss-Legendre nodes and weights on [0, 1], n points (exact for degree 2n-1).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// Gauss-Legendre on [0, 1] exact for polynomials of degree <= degree (0 <= degree <= 40): degree / 2 + 1 points,
// formed once. Weights sum to 1.
struct LineRule {
  std::vector<double> nodes, weights;
};
const LineRule& line_rule(int degree);

// Gauss-Jacobi nodes and weights on [0, 1] for the weight (1 - u)^alpha, n points:
// int_0^1 (1 - u)^alpha p(u) du = sum w_i p(u_i) for polynomials p of degree <= 2n - 1 (Golub-Welsch: the
// eigenvalues and first eigenvector components of the Jacobi matrix of the recurrence).
void gauss_jacobi(int n, int alpha, std::vector<double>& nodes, std::vector<double>& weights);

// Quadrature rules on the reference tetrahedron {(0,0,0), (1,0,0), (0,1,0), (0,0,1)} (FreeFEM's).
struct RulePoint3 {
  Point3 xi;      // reference coordinates
  double weight;  // weights sum to 1: the integral over a tetrahedron of volume V is V * sum(weight * f)
};

// A rule exact for polynomials of total degree <= degree (0 <= degree <= 40), all weights positive.
// Degrees 0-1: the centroid; 2: the symmetric 4-point rule (barycentric (a, a, a, 1 - 3a), a = (5 - sqrt 5)
// / 20); 4 and 5: the symmetric 14-point rule; 6 to 9: fully symmetric rules of 24, 35, 46 and 59 points solved
// for this project; 3 and from 10 on a collapsed (Duffy) product of Gauss-Jacobi rules (degree 3: 8 points),
//   int_T f = int_0^1 int_0^1 int_0^1 f(u, (1-u) v, (1-u)(1-v) w) (1-u)^2 (1-v) dw dv du,
// with ceil((degree + 1) / 2) points in each direction (weights (1-u)^2, (1-v) and 1 in the rules).
const std::vector<RulePoint3>& tetrahedron_rule(int degree);
// The same for integrands that are polynomials of degree <= degree, with fewer points: degrees 10 to 17 fully
// symmetric rules of 95, 119, 147, 171, 229, 265, 341 and 381 points solved for this project (in place of 216 to
// 729), the others tetrahedron_rule's. Newton's pull-backs (integrands that are not polynomials) keep
// tetrahedron_rule, whose products leave less of the remainder.
const std::vector<RulePoint3>& tetrahedron_rule_for_polynomials(int degree);

}  // namespace dlmfsi
