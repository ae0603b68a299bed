// The exact method: the image X(T) of a solid triangle is clipped against the fluid triangles it meets
// (fluid_search.hpp, clip.hpp) and each piece integrated in fluid coordinates,
//   int_T f(s) ds = int_{X(T)} f(X^-1(y)) |det grad X(X^-1(y))|^-1 dy,
// by a PieceIntegrator: with a rule exact for the product's degree where X is affine on T (exact to
// round-off), otherwise with Newton's pull-back and a rule of degree qforder or, by default,
// nonlinear_rule_degree of the map's nonlinearity (about 1e-13). An image too far from affine (nonlinearity
// above kLeafNonlinearity), or with curved edges (4^subdivide straight sub-triangles, default subdivide 2),
// is split into straight parts first (split.hpp), each with the rule of its own nonlinearity.
// On an affine triangle whose image is small against its distance from an axis (kLocalRatio), the image is
// clipped and integrated in coordinates relative to its first corner along that axis (local_origin): every
// decision of the clip is the same as in absolute coordinates, but the pieces' crossings and rule points are
// rounded to the image's size rather than to |y|, so the result does not depend on where the solid sits. When
// a fluid triangle met does not translate exactly, the image is done again in absolute coordinates.
// The area outside the fluid mesh is the image's area less the pieces'; below the round-off of the pieces'
// corners (MappedTriangle::area_round_off) it is 0.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "mesh/fluid_search.hpp"
#include "integration/integrator.hpp"

namespace dlmfsi {

class ExactMethod : public TriangleIntegrator {
 public:
  // search: on fluid's grid. general integrates the pieces, except those of affine images when affine is
  // given. qforder, subdivide: the options (-1 automatic).
  ExactMethod(const FluidSide& fluid, FluidSearch& search, int product_degree, int qforder, int subdivide,
              std::unique_ptr<PieceIntegrator> general, std::unique_ptr<PieceIntegrator> affine,
              CouplingReport& counts);
  double integrate(const MappedTriangle& mt, LocalBlock& block) override;

 private:
  // The rule for the whole image of mt: the product's degree where the map is affine; qforder when given;
  // -1 when the image must be split; otherwise nonlinear_rule_degree.
  int rule_degree(const MappedTriangle& mt);
  int rule_degree(double nonlinearity);
  // Clips the straight image img (the whole image or a part) and integrates its pieces; returns img's area
  // less the pieces'.
  double clip(const ClippedImage& image, const Point img[3], LocalBlock& block);
  // Per axis, img[0]'s coordinate where it is at least kLocalRatio times the image's size (its box's larger
  // side), else 0: then img translates exactly (Sterbenz), and so does any fluid corner within |origin| / 2.
  static Point local_origin(const Point img[3]);
  static constexpr double kLocalRatio = 1024;

  const FluidSide& fluid_;
  FluidSearch& search_;
  int hint_ = 0;  // a fluid triangle near the last image, where the search starts
  int product_degree_, qforder_, subdivide_;
  std::unique_ptr<PieceIntegrator> general_, affine_;
  CouplingReport& counts_;
  std::vector<MapPart> parts_;
  std::vector<std::pair<int, Piece>> local_pieces_;  // the pieces of an image in local coordinates, kept
  static constexpr int kMaxLeafDepth = 30, kMaxLeaves = 100000;  // split_image's limits
};

}  // namespace dlmfsi
