#include "integration/exact_method3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sides/report.hpp"
#include "sides/sides3d.hpp"
#include "errors.hpp"
#include "geometry/predicates3d.hpp"
#include "geometry/red_refinement3d.hpp"
#include "map/split3d.hpp"

namespace dlmfsi {

namespace {
using Tet = std::array<Point3, 4>;
}  // namespace

ExactMethod3::ExactMethod3(const FluidSide3& fluid, FluidSearch3& search, const Integrand3& integrand, int qforder,
                           int subdivide, std::unique_ptr<PieceIntegrator3> general,
                           std::unique_ptr<PieceIntegrator3> affine, CouplingReport& counts)
    : fluid_(fluid), search_(search), fluid_degree_(integrand.fluid_degree),
      multiplier_degree_(integrand.multiplier_degree), product_degree_(integrand.product_degree), qforder_(qforder),
      subdivide_(subdivide), general_(std::move(general)), affine_(std::move(affine)), counts_(counts) {}

double ExactMethod3::integrate(const MappedTet& mt, LocalBlock& block) {
  // On the reference side where the map and both bases are polynomial: a rule exact for psi (phi o X).
  const int map_degree = mt.fitted_degree();
  const bool reference_side = !mt.planar && map_degree >= 1 && fluid_degree_ >= 0 && multiplier_degree_ >= 0;
  // Curved faces: the reference tetrahedron refined, corners mapped by the true map; on each sub-tetrahedron
  // the jacobian varies 2^level times less. By default 2 levels; 1 on the reference side, whose band term
  // (PointIntegrator3::gather_band) makes 1 level more accurate than 2 without it, at the same cost.
  const int level = mt.planar ? 0 : (subdivide_ >= 0 ? subdivide_ : reference_side ? 1 : 2);
  int degree;
  if (reference_side) {
    degree = qforder_ >= 0 ? qforder_ : std::min(40, multiplier_degree_ + fluid_degree_ * map_degree);
    counts_.curved_rule_degree = std::max(counts_.curved_rule_degree, degree);
  } else {
    degree = rule_degree(mt, std::ldexp(1.0, -level), !mt.planar);
  }
  const ClippedImage3 image{mt, degree};
  if (mt.affine) return clip(image, mt.image, block);
  if (mt.planar) return clip_or_split(image, reference_subdivision(0)[0].data(), mt.image, block);
  double outside = 0;
  for (const Tet& sub : reference_subdivision(level)) {
    Point3 img[4];
    for (int i = 0; i < 4; ++i) {
      // at T's corners their images (the field's values where the map has them: a coincidence in the data, a
      // solid face mapped into a fluid plane, stays exact), elsewhere the fitted map's
      const Point3 r = sub[i];
      const int corner = r.x == 0 && r.y == 0 && r.z == 0 ? 0
                         : r.y == 0 && r.z == 0 && r.x == 1 ? 1
                         : r.x == 0 && r.z == 0 && r.y == 1 ? 2
                         : r.x == 0 && r.y == 0 && r.z == 1 ? 3
                                                            : -1;
      img[i] = corner >= 0 ? mt.image[corner] : mt.position(r);
      if (!std::isfinite(img[i].x) || !std::isfinite(img[i].y) || !std::isfinite(img[i].z))
        throw Error("the map is NaN or Inf inside solid tetrahedron " + std::to_string(mt.k));
    }
    ClippedImage3 part{mt, image.degree, sub.data(), img};
    part.reference_side = reference_side;
    outside += clip_or_split(part, sub.data(), img, block);
  }
  return outside;
}

double ExactMethod3::clip_or_split(const ClippedImage3& image, const Point3 xi[4], const Point3 y[4],
                                   LocalBlock& block) {
  const MappedTet& mt = image.tetrahedron;
  if (image.reference_side) {
    // the preimages of the pieces tile xi whatever the map's nonlinearity there; a split is needed only where
    // the straight image is not positively oriented, and would leave straight images that do not meet those of
    // the neighbours (the band's columns need them to)
    if (orient3d(y[0], y[1], y[2], y[3]) > 0) return clip(image, y, block);
    int parts = 0;
    const double outside = split_reference_side(image, xi, 1, parts, block);
    ++counts_.split;
    counts_.parts += parts;
    return outside;
  }
  if (qforder_ >= 0 || nonlinearity_on(mt, xi, y) <= kSplitNonlinearity3) return clip(image, y, block);
  if (!split_part3(mt, xi, y, kSplitNonlinearity3, kMaxPartDepth3, kMaxParts3, parts_)) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "the map nearly folds solid tetrahedron %d: its nonlinearity stays above %.3g on parts of 2^-%d of "
                  "its size, or on more than %d parts",
                  mt.k, kSplitNonlinearity3, kMaxPartDepth3, kMaxParts3);
    throw Error(msg);
  }
  ++counts_.split;
  counts_.parts += static_cast<long>(parts_.size());
  // Each part gets the rule of its own nonlinearity (a rule of 2^-level of the whole's on a sub-tetrahedron
  // of a curved image: the same scale).
  double outside = 0;
  for (const MapPart3& part : parts_) {
    ClippedImage3 piece{mt, part_rule_degree(part.nonlinearity, !mt.planar), part.xi, part.y};
    outside += clip(piece, part.y, block);
  }
  return outside;
}

// The reference side integrates on the preimages of the pieces, which must tile the reference tetrahedron:
// parts split in fluid coordinates (split3d.hpp) would not (their reference corners are pulled back from
// straight midpoints), so there the part xi is red-refined in reference coordinates, its corners mapped by X,
// until every part's straight image is positively oriented. Where a split part meets an unsplit neighbour the
// straight images differ by the map's deviation from its chords on their common face, which the band's
// columns do not see: the split is the exception (a sub-tetrahedron far larger than the map's curvature).
double ExactMethod3::split_reference_side(const ClippedImage3& image, const Point3 xi[4], int depth, int& parts,
                                          LocalBlock& block) {
  const MappedTet& mt = image.tetrahedron;
  double outside = 0;
  for (const Tet& child : reference_subdivision(1)) {
    Point3 cxi[4], cy[4];
    for (int i = 0; i < 4; ++i) {
      const Point3 r = child[i];
      cxi[i] = xi[0] + (r.x * (xi[1] - xi[0]) + r.y * (xi[2] - xi[0]) + r.z * (xi[3] - xi[0]));
      cy[i] = mt.position(cxi[i]);
    }
    if (orient3d(cy[0], cy[1], cy[2], cy[3]) <= 0) {
      if (depth >= kMaxPartDepth3 || parts + 8 > kMaxParts3) {
        char msg[300];
        std::snprintf(msg, sizeof msg,
                      "the map nearly folds solid tetrahedron %d: the straight images of its parts stay flat or "
                      "inverted down to parts of 2^-%d of its size, or on more than %d parts",
                      mt.k, depth, kMaxParts3);
        throw Error(msg);
      }
      outside += split_reference_side(image, cxi, depth + 1, parts, block);
      continue;
    }
    ++parts;
    ClippedImage3 part{mt, image.degree, cxi, cy};
    part.reference_side = true;
    outside += clip(part, cy, block);
  }
  return outside;
}

// Where the map is not affine, the integrand in fluid coordinates, f(X^-1(y)) / det grad X, is smooth but
// not polynomial; its error under a rule of degree p + q falls like (d/3)^q, d the map's nonlinearity (how
// far grad X strays from the affine jacobian, mapped_element3d.hpp; measured on P1b maps, d = 0.05 to 0.4, where
// q = 14 gives 1e-12 at d = 0.37). So q = 12 / -log10(d/3), at most 26 (d <= 1: images of larger d are split,
// clip_or_split), for an error about 1e-12 on planar images (a bubble map of d = 0.9 / 0.99: 3e-13 / 2e-13
// with q = 23 / 26, against 5e-11 / 1.6e-10 with 16); on curved images, whose error is the band between the
// curved boundary and the facets (1e-3 to 1e-6), 1e-8 (qforder overrides).
int ExactMethod3::rule_degree(const MappedTet& mt, double scale, bool curved) {
  if (mt.affine) return product_degree_;
  if (qforder_ >= 0) return qforder_;
  return part_rule_degree(scale * mt.nonlinearity, curved);
}

// Degree p + q, q the least with (nonlinearity / 3)^q below 1e-8 for curved images (subdivide's chords) and 1e-16
// for planar ones (a P1b map's: Newton's pull-back, the rule's error falling spectrally): on kinked data over many
// pieces the error is well above (nonlinearity / 3)^q, and 1e-12 (the target for lam^T B u) takes q for 1e-16: 3e-14
// for lam^T B u and 3e-13 for the entries on tests/edp/bench/p1b_accuracy3d.edp (with q for 1e-12: 2.3e-11 and
// 3.6e-11), for twice the points.
int ExactMethod3::part_rule_degree(double nonlinearity, bool curved) {
  const double d = std::max(nonlinearity, 1e-300) / 3;
  const double digits = curved ? 8 : 16;
  const int q = d >= 0.5 ? kMaxQ3 : std::min(kMaxQ3, std::max(2, static_cast<int>(std::ceil(digits / -std::log10(d)))));
  const int degree = std::min(40, product_degree_ + q);
  counts_.curved_rule_degree = std::max(counts_.curved_rule_degree, degree);
  return degree;
}

double ExactMethod3::clip(const ClippedImage3& image, const Point3 img[4], LocalBlock& block) {
  const int o = orient3d(img[0], img[1], img[2], img[3]);
  // Folds are refused before (MappedTet::prepare: the corners, the fold certificate): here the chords cross.
  if (o <= 0)
    throw Error("the straight image of a part of solid tetrahedron " + std::to_string(image.tetrahedron.k) + " is " +
                (o == 0 ? "flat" : "negatively oriented") +
                " although the map does not fold there (its chords cross): a larger subdivide may integrate it");
  PieceIntegrator3& integrator = affine_ && image.tetrahedron.affine ? *affine_ : *general_;
  double covered = 0;
  auto add_piece = [&](const ClippedImage3& in, int kf, const Piece3& piece) {
    ++counts_.pieces;
    block.enter_fluid_element(fluid_.dofs(kf));
    covered += integrator.integrate(in, kf, piece, block);
  };
  // The image's volume: volume6 of the exactly translated corners equals volume6 of img bit for bit.
  const double volume = volume6(img[0], img[1], img[2], img[3]) / 6;
  // Local coordinates for affine images and for the straight images of the reference side (whose pieces go
  // back through the affine interpolant and the map's displacement, both local); Newton's pull-back works in
  // absolute coordinates.
  const bool in_local = (image.tetrahedron.affine && !image.sub_xi) || image.reference_side;
  const Point3 origin = in_local ? local_origin(img) : Point3();
  if (origin != Point3()) {
    const int hint = hint_;
    local_pieces_.clear();
    const bool exact = search_.for_each_piece(img, origin, hint_, [&](int kf, const Piece3& piece) {
      local_pieces_.emplace_back(kf, piece);
    });
    if (exact) {
      ClippedImage3 local = image;
      local.origin = origin;
      integrator.start(local);
      for (const auto& [kf, piece] : local_pieces_) add_piece(local, kf, piece);
      integrator.finish(local, block);
      return volume - covered;
    }
    hint_ = hint;  // in absolute coordinates, from the same start
  }
  integrator.start(image);
  search_.for_each_piece(img, hint_, [&](int kf, const Piece3& piece) { add_piece(image, kf, piece); });
  integrator.finish(image, block);
  return volume - covered;
}

Point3 ExactMethod3::local_origin(const Point3 img[4]) {
  Point3 lo = img[0], hi = img[0];
  for (int i = 1; i < 4; ++i) {
    lo = {std::min(lo.x, img[i].x), std::min(lo.y, img[i].y), std::min(lo.z, img[i].z)};
    hi = {std::max(hi.x, img[i].x), std::max(hi.y, img[i].y), std::max(hi.z, img[i].z)};
  }
  const double far = kLocalRatio * std::max(hi.x - lo.x, std::max(hi.y - lo.y, hi.z - lo.z));
  auto axis = [far](double v) { return std::fabs(v) >= far ? v : 0.0; };
  return {axis(img[0].x), axis(img[0].y), axis(img[0].z)};
}

}  // namespace dlmfsi
