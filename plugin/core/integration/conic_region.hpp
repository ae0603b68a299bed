// A rule for a smooth function over the part of a convex polygon where a quadratic has a given sign:
//   int_{p in polygon, sign q(p) > 0} f(p) dA,   q(u, v) = c0 + cu u + cv v + cuu u^2 + cuv u v + cvv v^2,
// to the accuracy of Gauss-Legendre on smooth integrands (spectral), not by cutting the region into facets.
// The plane is turned so that the inner lines (t) run along the gradient of q at the polygon's centroid; along
// each line the roots of q (a quadratic in t) bound the region exactly, and the outer integral (s) is split
// where the inner one is not smooth: at the polygon's vertices, where q = 0 crosses an edge, and where the
// curve q = 0 has a tangent along t (q = dq/dt = 0: the inner length behaves like sqrt(s - s_t) there, so an
// interval near a real tangent runs its outer rule in sigma, s = s_t +- sigma^2, in which it is smooth, and an
// interval with another tangent, real or complex, too close for its rule is halved: conic_region.cpp).
#pragma once
#include <vector>

#include "fe/rules.hpp"

namespace dlmfsi {

struct Quadratic2 {
  double c0 = 0, cu = 0, cv = 0, cuu = 0, cuv = 0, cvv = 0;
  double at(double u, double v) const { return c0 + u * (cu + cuu * u + cuv * v) + v * (cv + cvv * v); }
};

struct RegionPoint2 {
  double u, v, weight;
};

// Appends to out the points of the rule for {p in polygon : sign q(p) > 0} (sign +1 or -1), polygon convex
// with m >= 3 vertices (u, v) in either order; outer and inner: the line rules (on [0, 1]) along s and t; degree:
// the integrand's polynomial degree, which the outer rule's convergence near a tangent must make up for.
void conic_region_rule(const double (*polygon)[2], int m, const Quadratic2& q, int sign, const LineRule& outer,
                       const LineRule& inner, int degree, std::vector<RegionPoint2>& out);

}  // namespace dlmfsi
