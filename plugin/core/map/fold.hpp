// Does a polynomial map fold a triangle? Its jacobian determinant is certified positive on the whole
// reference triangle, not only at sample points.
//
// For a map of degree d, det dX/dxi is a polynomial of degree n = 2(d - 1) in the reference coordinates.
// Written in the Bernstein basis of degree n on a sub-triangle (from its values at the sub-triangle's
// degree-n lattice), its values there lie between the smallest and the largest coefficient, since the
// Bernstein polynomials are non-negative and sum to one. So, on each sub-triangle:
//  - every coefficient above 1e-12 of the largest value: det > 0 there;
//  - a value at a lattice point <= 0: the map folds or flattens there;
//  - otherwise split it into 4 (the coefficients converge to the values as h^2) and test the parts, down to
//    max_depth levels; what is left undecided has det within about 4^-max_depth of zero relative to its
//    scale, and is reported as a (near) fold.
#pragma once
#include <functional>

#include "point.hpp"
#include "map/element_map.hpp"

namespace dlmfsi {

enum class JacobianSign { Positive, Folds, NearlyFolds };

// det(xi): the jacobian determinant at a reference point, a polynomial of degree n (0 <= n <= 10).
// where: a reference point at which det <= 0 (Folds) or the centre of an undecided sub-triangle.
JacobianSign jacobian_sign(const std::function<double(Point)>& det, int n, int max_depth, Point& where);

// A sufficient condition, from a fitted map's coefficients alone: true when det dX/dxi is at least a quarter
// of that of the affine interpolant of the corner images on the whole reference triangle (maps near affine,
// such as the bubbles of a P1b map of a smooth motion); false when not fitted or not decided so.
bool jacobian_certainly_positive(const TriangleMap& map);

// Throws Error naming the triangle when det dX/ds is not positive somewhere on the triangle of map (a fold)
// or comes within about 1e-6 of zero relative to its scale (a near fold): certified by
// jacobian_certainly_positive or else by jacobian_sign with max_depth 10 for a fitted map, sampled on the
// degree-8 lattice otherwise.
void check_fold(const TriangleMap& map);

}  // namespace dlmfsi
