// The exact method for tetrahedra: the image X(T) of a solid tetrahedron is clipped against the fluid
// tetrahedra it meets (fluid_search3d.hpp, clip3d.hpp) and each piece integrated in fluid coordinates,
//   int_T f(s) ds = int_{X(T)} f(X^-1(y)) |det grad X(X^-1(y))|^-1 dy,
// by a PieceIntegrator3: with a rule exact for the product's degree where X is affine on T, otherwise with
// Newton's pull-back and a rule of degree qforder or, by default, one chosen from the map's nonlinearity.
// Images whose faces are planar (P1b maps) are clipped whole; curved ones (P2 maps) are replaced by the
// images of the 8^subdivide tetrahedra of the refined reference tetrahedron (default subdivide 2).
// The volume outside the fluid mesh is the image's volume less the pieces'.
#pragma once
#include <memory>

#include "integrator3d.hpp"

namespace dlmfsi {

class ExactMethod3 : public TetrahedronIntegrator {
 public:
  // search: on fluid's grid. general integrates the pieces, except those of affine images when affine is
  // given. qforder, subdivide: the options (-1 automatic).
  ExactMethod3(const FluidSide3& fluid, FluidSearch3& search, int product_degree, int qforder, int subdivide,
               std::unique_ptr<PieceIntegrator3> general, std::unique_ptr<PieceIntegrator3> affine,
               CouplingReport3& counts);
  double integrate(const MappedTet& mt, LocalBlock& block) override;

 private:
  // The rule for mt: the product's degree where the map is affine, else qforder or a degree from the
  // nonlinearity; scale: the jacobian's variation on a sub-tetrahedron relative to the whole.
  int rule_degree(const MappedTet& mt, double scale, bool curved);
  // Clips the straight tetrahedron img (the image, or a sub-tetrahedron's) and integrates its pieces;
  // returns img's volume less the pieces'.
  double clip(const ClippedImage3& image, const Point3 img[4], LocalBlock& block);

  const FluidSide3& fluid_;
  FluidSearch3& search_;
  int hint_ = 0;  // a fluid tetrahedron near the last image, where the search starts
  int product_degree_, qforder_, subdivide_;
  std::unique_ptr<PieceIntegrator3> general_, affine_;
  CouplingReport3& counts_;
};

}  // namespace dlmfsi
