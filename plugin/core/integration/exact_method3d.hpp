// The exact method for tetrahedra: the image X(T) of a solid tetrahedron is clipped against the fluid
// tetrahedra it meets (fluid_search3d.hpp, clip3d.hpp) and each piece integrated in fluid coordinates,
//   int_T f(s) ds = int_{X(T)} f(X^-1(y)) |det grad X(X^-1(y))|^-1 dy,
// by a PieceIntegrator3: with a rule exact for the product's degree where X is affine on T, otherwise with
// Newton's pull-back and a rule of degree qforder or, by default, one chosen from the map's nonlinearity.
// Images whose faces are planar (P1b maps) are clipped whole. Curved ones (P2 maps) are replaced by the
// images of the 8^subdivide tetrahedra T_i of the refined reference tetrahedron (default subdivide 1 on the
// reference side below, 2 otherwise), each
// straight image A_i(T_i) (A_i the affine interpolant of X at T_i's corners) clipped against the fluid; with
// polynomial bases and map the pieces are integrated on the reference side (ClippedImage3::reference_side):
//   int_T f(s) ds = sum_i sum_K int_{A_i^-1(A_i(T_i) ∩ K)} psi(s) phi_K(X(s)) ds,
// the preimages tiling T exactly and the integrand a polynomial of degree m + f d (multiplier, fluid, map),
// integrated exactly. Only which fluid tetrahedron's polynomial is used where differs from the exact
// integral: in the band between A_i^-1 and X^-1 of a fluid face, of width delta = O(h_i^2) (h_i: T_i's
// size). The band is added in columns along a solid axis (PointIntegrator3::gather_band), exact for a kink
// along one fluid plane; where fluid faces meet inside the solid, O(delta^2) per unit length is left. On the
// reference side a straight image is split only where it is not positively oriented, in reference coordinates
// (split_reference_side); elsewhere a straight image (or sub-tetrahedron) on which the map is far from affine,
// near a fold, is split in fluid coordinates into nearly affine parts (split3d.hpp), each with the rule of its
// own nonlinearity. The volume outside the fluid mesh is the image's volume less the pieces'.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "integration/integrator3d.hpp"
#include "map/split3d.hpp"

namespace dlmfsi {

class ExactMethod3 : public TetrahedronIntegrator {
 public:
  // search: on fluid's grid. general integrates the pieces, except those of affine images when affine is
  // given. qforder, subdivide: the options (-1 automatic).
  ExactMethod3(const FluidSide3& fluid, FluidSearch3& search, const Integrand3& integrand, int qforder, int subdivide,
               std::unique_ptr<PieceIntegrator3> general, std::unique_ptr<PieceIntegrator3> affine,
               CouplingReport& counts);
  double integrate(const MappedTet& mt, LocalBlock& block) override;

 private:
  // The rule for mt: the product's degree where the map is affine, else qforder or a degree from the
  // nonlinearity; scale: the jacobian's variation on a sub-tetrahedron relative to the whole.
  int rule_degree(const MappedTet& mt, double scale, bool curved);
  // Clips the straight tetrahedron img (the image, or a sub-tetrahedron's) and integrates its pieces;
  // returns img's volume less the pieces'.
  double clip(const ClippedImage3& image, const Point3 img[4], LocalBlock& block);
  // Per axis, img[0]'s coordinate where it is at least kLocalRatio times the image's size (its box's largest
  // side), else 0. An affine image far from the origin against its size is clipped and integrated relative
  // to it, as in 2D (ExactMethod): every decision as in absolute coordinates, the constructed points rounded
  // to the image's size; in absolute coordinates when a fluid tetrahedron met does not translate exactly.
  static Point3 local_origin(const Point3 img[4]);
  static constexpr double kLocalRatio = 1024;
  // clip(), or where the map's nonlinearity on the straight tetrahedron y (the images of the reference
  // points xi) is above kSplitNonlinearity3 and qforder is automatic, clip() of its parts (split3d.hpp),
  // each with the rule of its own nonlinearity (on the reference side, clip() unless y is not positively
  // oriented, then split_reference_side's parts); throws Error when the split needs more than its limits.
  double clip_or_split(const ClippedImage3& image, const Point3 xi[4], const Point3 y[4], LocalBlock& block);
  // On the reference side: xi red-refined in reference coordinates until every part's straight image is
  // positively oriented (the same limits), each part clipped; parts counts them.
  double split_reference_side(const ClippedImage3& image, const Point3 xi[4], int depth, int& parts,
                              LocalBlock& block);
  // The rule for a part of nonlinearity d (rule_degree's formula with scale 1).
  int part_rule_degree(double nonlinearity, bool curved);
  static constexpr int kMaxQ3 = 26;  // the highest automatic degree above the product's

  // Images (or sub-tetrahedra) of nonlinearity_on above 1 are split into parts of nonlinearity <= 1, at most
  // 20 levels down and 20000 parts per straight tetrahedron split (rule_degree: up to p + 26 below 1).
  // Measured on single tetrahedra (tests/core/test_fold3d.cpp, each within 1e-12), relative errors with the
  // planar images' rule for 1e-12 (part_rule_degree): a P1b-like bubble map of nonlinearity 0.6 / 0.9 / 1.5:
  // 1.5e-13 / 2.8e-13 unsplit, 9.4e-14 split into 386 parts (3e-8 with one rule of p + 16); a P2 map with an edge
  // midpoint slid by 0.1 / 0.2 (nonlinearity 1.2 / 2.4): 5e-14 / 9e-14 in 8 / 239 parts (4e-15 / 3e-9 with one
  // rule of p + 16).
  static constexpr double kSplitNonlinearity3 = 1;
  static constexpr int kMaxPartDepth3 = 20, kMaxParts3 = 20000;
  std::vector<MapPart3> parts_;
  std::vector<std::pair<int, Piece3>> local_pieces_;  // the pieces of an image in local coordinates, kept

  const FluidSide3& fluid_;
  FluidSearch3& search_;
  int hint_ = 0;  // a fluid tetrahedron near the last image, where the search starts
  // the bases' degrees (the integrand's: -1 when not polynomial) and the product's
  int fluid_degree_, multiplier_degree_, product_degree_, qforder_, subdivide_;
  std::unique_ptr<PieceIntegrator3> general_, affine_;
  CouplingReport& counts_;
};

}  // namespace dlmfsi
