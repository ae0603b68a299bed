// The integrator interface (integrator.hpp) for tetrahedra: the integrand over the same spaces in 3D, the
// clipped image of a solid tetrahedron, and the selection of the integrators.
//
// A TetrahedronIntegrator adds int_T f_ij ds over a solid tetrahedron T to the tetrahedron's LocalBlock: the
// quadrature method (quadrature_method3d.hpp) sums a rule with each point located in the fluid, the
// exact method (exact_method3d.hpp) clips T's image against the fluid and hands each piece to a
// PieceIntegrator3: point by point through either basis and either gradient product (integrate_points3d.hpp),
// or, on affine images with the chain rule, from the piece's moments: its volume, centroid and second
// moments for bases of degree <= 1 (integrate_moments3d.hpp), its monomial moments in the fluid element for
// a fluid of higher degree and a multiplier of degree <= 1 (integrate_monomials3d.hpp).
#pragma once
#include <memory>

#include "geometry/clip3d.hpp"
#include "mesh/fluid_search3d.hpp"
#include "integration/integrator.hpp"
#include "map/mapped_element3d.hpp"
#include "fe/polynomial_basis3d.hpp"

namespace dlmfsi {

class FluidSide3;
struct CouplingReport;

using Integrand3 = IntegrandOf<Basis3, PolynomialBasis3>;

// The straight image of a solid tetrahedron, or of one of the sub-tetrahedra of a curved one, clipped
// against the fluid: its pieces are clipped in coordinates relative to origin, y_local = y - origin (0 except
// on images far from it against their size, below; as ClippedImage in 2D).
struct ClippedImage3 {
  const MappedTet& tetrahedron;
  int degree;  // of the rule on a piece: exact for the integrand where the map is affine, and on the reference side
  // For a sub-tetrahedron: its reference corners and their images, whose affine interpolant gives Newton's
  // first guess (null for the whole image: MappedTet::affine_reference).
  const Point3* sub_xi = nullptr;
  const Point3* sub_y = nullptr;
  // Nonzero only on affine tetrahedra and on the reference side's sub-tetrahedra, far from the origin against
  // their size (ExactMethod3::local_origin); Newton's pull-back works in absolute coordinates.
  Point3 origin = {};
  // Integrate on the reference side (a sub-tetrahedron of a curved image, ExactMethod3): a point of a piece is
  // taken back by the sub-tetrahedron's affine interpolant (guess(), no Newton) and the fluid is evaluated at
  // the map's value there, so that the pieces' preimages tile the solid tetrahedron and the integrand is a
  // polynomial in the reference coordinates.
  bool reference_side = false;
  // Newton's first guess for the reference point of y_local (the pull-back itself on an affine tetrahedron).
  Point3 guess(Point3 y) const;
};

// Adds the integrand over one piece (image ∩ fluid tetrahedron kf) to the block (the caller has entered kf
// in the block) and returns the piece's volume as the integrator sums it: |volume6| / 6 of each of the
// piece's tetrahedra, in Piece3::for_each_tetrahedron's order (so the image's volume outside the fluid is
// found without a second pass over the piece).
class PieceIntegrator3 {
 public:
  virtual ~PieceIntegrator3() = default;
  // Before the pieces of an image (the caller calls it): what does not change from piece to piece may be
  // formed here, once.
  virtual void start(const ClippedImage3& /*image*/) {}
  virtual double integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) = 0;
  // After the pieces of an image: what is integrated per image rather than per piece.
  virtual void finish(const ClippedImage3& /*image*/, LocalBlock& /*block*/) {}
};
using TetrahedronIntegrator = ElementIntegratorOf<MappedTet>;

}  // namespace dlmfsi
