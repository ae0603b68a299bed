#include "integration/exact_method.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "sides/report.hpp"
#include "sides/sides.hpp"
#include "errors.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

ExactMethod::ExactMethod(const FluidSide& fluid, FluidSearch& search, int product_degree, int qforder, int subdivide,
                         std::unique_ptr<PieceIntegrator> general, std::unique_ptr<PieceIntegrator> affine,
                         CouplingReport& counts)
    : fluid_(fluid), search_(search), product_degree_(product_degree), qforder_(qforder),
      subdivide_(subdivide), general_(std::move(general)), affine_(std::move(affine)), counts_(counts) {}

double ExactMethod::integrate(const MappedTriangle& mt, LocalBlock& block) {
  const long pieces = counts_.pieces;
  double outside = 0;
  const int degree = rule_degree(mt);
  if (mt.straight && degree >= 0) {
    outside = clip({mt, degree, nullptr}, mt.image, block);
  } else {
    // Curved edges (2^L x 2^L chords), or a map too far from affine for one rule (leaves until nearly
    // affine): straight parts, each with the pull-backs of its corners.
    const int level = mt.straight ? 0 : (subdivide_ >= 0 ? subdivide_ : 2);
    const double target = degree >= 0 ? std::numeric_limits<double>::infinity() : kLeafNonlinearity;
    if (!split_image(mt, level, target, kMaxLeafDepth, kMaxLeaves, parts_)) {
      char msg[240];
      std::snprintf(msg, sizeof msg,
                    "the map nearly folds solid triangle %d: its nonlinearity (%.3g on the triangle) stays above %.3g "
                    "on parts of 2^-%d of its size, or on more than %d parts",
                    mt.k, mt.nonlinearity, kLeafNonlinearity, kMaxLeafDepth, kMaxLeaves);
      throw Error(msg);
    }
    ++counts_.split;
    counts_.parts += static_cast<long>(parts_.size());
    // Each part gets the rule of its own nonlinearity (smaller than the triangle's), or qforder.
    for (const MapPart& part : parts_)
      outside += clip({mt, qforder_ >= 0 ? qforder_ : rule_degree(part.nonlinearity), &part}, part.y, block);
  }
  // the image area less the pieces' areas: zero up to the round-off of the pieces' corners
  if (outside > 0 && outside < mt.area_round_off(counts_.pieces - pieces)) outside = 0;
  return outside;
}

int ExactMethod::rule_degree(const MappedTriangle& mt) {
  if (mt.affine) return product_degree_;
  if (qforder_ >= 0) return qforder_;
  if (mt.nonlinearity > kLeafNonlinearity) return -1;
  return rule_degree(mt.nonlinearity);
}

int ExactMethod::rule_degree(double nonlinearity) {
  const int degree = nonlinear_rule_degree(product_degree_, nonlinearity);
  counts_.curved_rule_degree = std::max(counts_.curved_rule_degree, degree);
  return degree;
}

double ExactMethod::clip(const ClippedImage& image, const Point img[3], LocalBlock& block) {
  const int o = orient2d(img[0], img[1], img[2]);
  // Folds are refused before (MappedTriangle::prepare: the corners, the fold certificate): here the chords cross.
  if (o <= 0) throw crossed_chords(image.triangle.k, o);
  PieceIntegrator& integrator = image.triangle.affine && affine_ ? *affine_ : *general_;
  double covered = 0;
  auto add_piece = [&](const ClippedImage& in, int kf, const Piece& piece) {
    ++counts_.pieces;
    block.enter_fluid_element(fluid_.dofs(kf));
    covered += integrator.integrate(in, kf, piece, block);
  };
  // The image's area: area2 of the exactly translated corners equals area2 of img bit for bit.
  const double area = 0.5 * area2(img[0], img[1], img[2]);
  const Point origin = image.triangle.affine && !image.part ? local_origin(img) : Point();
  if (origin != Point()) {
    const int hint = hint_;
    local_pieces_.clear();
    const bool exact = search_.for_each_piece(img, origin, hint_, [&](int kf, const Piece& piece) {
      local_pieces_.emplace_back(kf, piece);
    });
    if (exact) {
      const ClippedImage local{image.triangle, image.degree, image.part, origin};
      integrator.start(local);
      for (const auto& [kf, piece] : local_pieces_) add_piece(local, kf, piece);
      return area - covered;
    }
    hint_ = hint;  // in absolute coordinates, from the same start
  }
  integrator.start(image);
  search_.for_each_piece(img, hint_, [&](int kf, const Piece& piece) { add_piece(image, kf, piece); });
  return area - covered;
}

Point ExactMethod::local_origin(const Point img[3]) {
  const double size = std::max(std::max(img[0].x, std::max(img[1].x, img[2].x)) -
                                   std::min(img[0].x, std::min(img[1].x, img[2].x)),
                               std::max(img[0].y, std::max(img[1].y, img[2].y)) -
                                   std::min(img[0].y, std::min(img[1].y, img[2].y)));
  const double far = kLocalRatio * size;
  return {std::fabs(img[0].x) >= far ? img[0].x : 0.0, std::fabs(img[0].y) >= far ? img[0].y : 0.0};
}

}  // namespace dlmfsi
