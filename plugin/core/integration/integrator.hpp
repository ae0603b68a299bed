// How the coupling's integrand is integrated over one solid triangle. The integrand, for multiplier function
// psi_i and fluid function phi_j of a coupled component pair, is
//   f_ij(s) = c2 psi_i(s) . phi_j(X(s)) + c1 grad_s psi_i : grad_s (phi_j o X)(s),
// with the chain rule grad_s (phi o X) = (grad phi)(X) dX/ds, or the printed listings' reversed product.
//
// A TriangleIntegrator adds int_T f_ij ds over a solid triangle T to the triangle's LocalBlock: the exact
// method (exact_method.hpp) clips T's image against the fluid and hands each piece to a PieceIntegrator;
// the quadrature method (quadrature_method.hpp) applies a composite rule on T. The piece integrators:
// point by point through either basis (integrate_points.hpp), in batches over fitted bases
// (integrate_batch.hpp), and from a piece's moments for bases of degree <= 1 (integrate_moments.hpp).
// choose_integrator (choose_integrator.hpp) picks them, once per call and thread.
//
// IntegrandOf and ElementIntegratorOf are templates on the dimension's spaces and mapped element, shared by
// the tetrahedral assembly (integrator3d.hpp: Integrand3, TetrahedronIntegrator, with the same LocalBlock);
// its piece integrators (PieceIntegrator3) take a Piece3, so they have an interface of their own.
#pragma once
#include <memory>

#include "geometry/clip.hpp"
#include "fe/component_pairs.hpp"
#include "mesh/fluid_search.hpp"
#include "integration/local_block.hpp"
#include "map/mapped_element.hpp"
#include "sides/options.hpp"
#include "fe/polynomial_basis.hpp"
#include "map/split.hpp"

namespace dlmfsi {

class FluidSide;
struct CouplingReport;

// What every integrator of one call reads (shared by the threads). Space: BasisOf<D>; Fit: its fitted basis.
template <class Space, class Fit>
struct IntegrandOf {
  const Space& fluid_space;  // the fluid side's space (renumbered, scaled coordinates)
  const Fit& fluid;          // its fitted basis on the coupled components
  const Space& multiplier_space;
  const Fit& multiplier;
  const ComponentPairs& pairs;
  double c1, c2;
  bool chain;  // the chain rule; otherwise the listings' product (applies where c1 != 0)
  // The bases' polynomial degrees (polynomial_degree: -1 when not polynomial), and the degree of a rule
  // exact for their product (affine maps).
  int fluid_degree, multiplier_degree, product_degree;
};
using Integrand = IntegrandOf<Basis, PolynomialBasis>;

// The straight image (or part of a split image, split.hpp) of a solid triangle that is clipped against the
// fluid: its pieces are integrated in fluid coordinates relative to origin, y_local = y - origin. The origin is
// 0 except on affine triangles far from it against their size (ExactMethod), where the image's corners and the
// corners of every fluid triangle it meets translate exactly (FluidSearchOf::for_each_piece with an origin):
// the fluid basis is then evaluated at A_K^-1(y_local - (v0_K - origin)) and the affine pull-back is
// A^-1(y_local - (image[0] - origin)), both differences formed in local coordinates.
struct ClippedImage {
  const MappedTriangle& triangle;
  int degree;           // of the rule on a piece where the map is not affine (exact for the product where it is)
  const MapPart* part;  // the part of a split image, or nullptr for the whole image
  Point origin = {};    // nonzero only on affine triangles (Newton's pull-back works in absolute coordinates)

  // The reference point of fluid point y_local in the solid triangle: the affine pull-back, or Newton's from
  // the affine guess of the triangle or, in a part, of the part.
  Point pull_back(Point y_local) const {
    if (triangle.affine) return triangle.affine_reference(y_local, origin);
    MapValue at;
    return triangle.pull_back(y_local, guess(y_local), at);
  }
  // Newton's starting point for y_local: the affine pull-back of the triangle or, in a part, of the part (the
  // pull-back itself on an affine triangle).
  Point guess(Point y_local) const {
    if (part) return from_reference(part->xi, to_reference(part->y, y_local));
    return triangle.affine_reference(y_local, origin);
  }
};

// Adds the integrand over one piece (image ∩ fluid element kf) to the block; the caller has entered fluid
// element kf in the block, and called start(image) before the image's first piece. Returns the piece's area,
// piece.area() bit for bit (an integrator that forms it anyway hands it back).
class PieceIntegrator {
 public:
  virtual ~PieceIntegrator() = default;
  // Before the pieces of an image: what does not change from piece to piece may be formed here, once.
  virtual void start(const ClippedImage& /*image*/) {}
  virtual double integrate(const ClippedImage& image, int kf, const Piece& piece, LocalBlock& block) = 0;
};

// Adds the integrand over one mapped solid element to the block (started by the caller on that element);
// returns the area (volume) of its image outside the fluid mesh, >= 0 up to round-off.
template <class MappedElement>
class ElementIntegratorOf {
 public:
  virtual ~ElementIntegratorOf() = default;
  virtual double integrate(const MappedElement& element, LocalBlock& block) = 0;
};
using TriangleIntegrator = ElementIntegratorOf<MappedTriangle>;

// Images of triangles whose nonlinearity (map_shape.hpp) is above this are split into parts on which it is at
// most this (split.hpp), where nonlinear_rule_degree gives a rule of degree p + 20.
constexpr double kLeafNonlinearity = 0.25;

// Where the map is not affine, the integrand in fluid coordinates is f(X^-1(y)) / det grad X, a series in
// the map's nonlinearity d whose k-th term is a polynomial of degree about p + 2k (p = product_degree), so
// degree p + 2k leaves about (d / 3)^(k+1) (measured on single triangles with P1b bubbles and P2 maps,
// d = 0.009 to 0.3: the relative error falls by about d / 3 for each 2 degrees, and below 1e-13 for the k
// chosen here: the smallest with (d / 3)^(k+1) <= 1e-11). d is taken in [1e-300, kLeafNonlinearity];
// the degree is at most kMaxQforder.
int nonlinear_rule_degree(int product_degree, double nonlinearity);

}  // namespace dlmfsi
