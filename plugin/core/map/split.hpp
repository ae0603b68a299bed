// The image of a solid triangle under a map far from affine (or with curved edges), as straight triangles
// ("parts") on each of which the map is nearly affine.
//
// On a piece of the image the coupling integrates f(X^-1(y)) / det dX(X^-1(y)) in fluid coordinates y; a
// rule of degree p + 2k is accurate when the map's nonlinearity (MappedTriangle::nonlinearity) is small,
// and converges slowly near a fold, where det dX vanishes. The nonlinearity on a part of the reference
// triangle falls with its size, so the reference triangle is split (in the solid's coordinates, where the
// integrand has no singularity) into leaves until the map is nearly affine on each:
//  - `level` uniform halvings first (the chords of curved images), then halvings of the leaves whose
//    nonlinearity is above `target`, down to max_depth further levels;
//  - each leaf's image is replaced by the polygon through the images of its corners and of the corners of
//    finer neighbours that lie on its edges, fanned from the image of its centroid (a single triangle when
//    no neighbour is finer). Neighbouring leaves then share their boundary polylines, so the parts tile
//    the polygon through the images of the outer boundary's points: the image itself where its edges are
//    straight (P1b maps). Curved edges are replaced by the chords between the images of their level-L
//    points (points of finer leaves on them are placed on these chords), the same chords as the
//    neighbouring solid triangle's: the parts of all triangles tile the solid's chord polygon.
// Leaf corners are dyadic points of the reference triangle, exact in floating point, so shared corners and
// hanging points are found by exact comparison.
#pragma once
#include <vector>

#include "errors.hpp"
#include "map/mapped_element.hpp"

namespace dlmfsi {

struct MapPart {
  Point y[3];           // the part, counter-clockwise, in fluid coordinates
  Point xi[3];          // reference points whose images are its corners (Newton's starts inside the part)
  double nonlinearity;  // of the map on the leaf it comes from
};

// Fills parts; returns false when a leaf still above target needs more than max_depth further halvings or
// the leaves would exceed max_leaves (the map nearly folds). Throws crossed_chords when a part's image is flat
// or clockwise.
bool split_image(const MappedTriangle& mt, int level, double target, int max_depth, int max_leaves,
                 std::vector<MapPart>& parts);

// The error for a straight image of a part of solid triangle k that is flat (orientation 0) or clockwise while
// the map does not fold there (MappedTriangle::prepare refuses folds first): its chords cross.
Error crossed_chords(int k, int orientation);

}  // namespace dlmfsi
