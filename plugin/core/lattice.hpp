// Polynomials on the reference triangle: monomials xi1^a xi2^b (a + b <= d) and interpolation on the
// equispaced lattice of degree d, used to turn a basis or a map into a cheap polynomial on one triangle.
#pragma once
#include <vector>

#include "point.hpp"

namespace dlmfsi {

constexpr int kMaxLatticeDegree = 8;
constexpr int monomial_count(int d) { return (d + 1) * (d + 2) / 2; }

// Monomial m is xi1^a xi2^b, listed by total degree t = a + b, then b = 0..t.
void monomial_exponents(int m, int& a, int& b);

// Lattice point m of degree d >= 1: (a/d, b/d) with the exponents of monomial m (d = 0: the centroid).
Point lattice_point(int d, int m);

// Row-major inverse of the Vandermonde matrix V[p][m] = monomial m at lattice point p: the monomial
// coefficients of a polynomial of degree d are inverse * (its values at the lattice points).
const std::vector<double>& vandermonde_inverse(int d);

// Values of all monomials of degree <= d at xi, and their derivatives in xi1 and xi2.
void monomials(int d, Point xi, double* value, double* d1, double* d2);

}  // namespace dlmfsi
