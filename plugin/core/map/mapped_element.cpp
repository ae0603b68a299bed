#include "map/mapped_element.hpp"

#include <algorithm>
#include <cmath>

#include "errors.hpp"
#include "map/fold.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

void MappedTriangle::prepare(const Mesh& solid_mesh, const SolidMap& map, int kk) {
  fit(solid_mesh, map, kk);
  // The image edges f1, f2: a fitted map's to the precision of the image's size (corner_displacement), the
  // corners origin() + f1, origin() + f2.
  Point f1, f2;
  if (fitted()) {
    f1 = corner_displacement(1);
    f2 = corner_displacement(2);
    image[0] = origin();
    image[1] = origin() + f1;
    image[2] = origin() + f2;
  } else {
    for (int i = 0; i < 3; ++i) image[i] = corner_image(i);
    f1 = image[1] - image[0];
    f2 = image[2] - image[0];
  }
  // c * 0 is 0 for a finite c, NaN for NaN or Inf
  if (image[0].x * 0 + image[0].y * 0 + image[1].x * 0 + image[1].y * 0 + image[2].x * 0 + image[2].y * 0 != 0)
    throw Error("the map is NaN or Inf at a corner of " + name());
  const int o = orient2d(image[0], image[1], image[2]);
  if (o == 0) throw Error("the map flattens " + name() + " (its image has zero area)");
  // (the message formed only when it is thrown: prepare runs for every solid triangle of every call)
  auto inverts = [this] {
    return Error("the map inverts " + name() + " (its image is clockwise: a reflection or a fold)");
  };
  if (o < 0 && degree() == 1) throw inverts();
  // A^-1 = [f1 f2]^-1
  const double di = cross(f1, f2);
  image_inv_[0][0] = f2.y / di;
  image_inv_[0][1] = -f2.x / di;
  image_inv_[1][0] = -f1.y / di;
  image_inv_[1][1] = f1.x / di;
  if (degree() == 1) {  // a P1 map: affine and straight by construction
    straight = affine = true;
    nonlinearity = 0;
  } else {
    const MapShape shape = map_shape(*this, image, image_inv_, magnitude());
    affine = shape.affine;
    straight = shape.straight;
    nonlinearity = shape.nonlinearity;
    // Corner images clockwise: with straight edges the image itself is inverted. A curved map may still be one
    // to one (a thin triangle whose apex a smooth map moves across the opposite edge's chord): the fold
    // certificate decides, and the curved method follows the true edges.
    if (o < 0 && (affine || straight)) throw inverts();
    if (!affine) {
      check_fold(*this);
      const double inv_norm = std::max(std::fabs(image_inv_[0][0]) + std::fabs(image_inv_[0][1]),
                                       std::fabs(image_inv_[1][0]) + std::fabs(image_inv_[1][1]));
      // a fitted map's residuals are relative to image[0] (newton_pull_back): their round-off is eps times
      // the image's size, not its distance from 0
      xi_round_off_ = 8 * kEps * (fitted() ? extent(f1, f2) : magnitude()) * inv_norm;
    }
  }
  if (!affine) return;
  // dX/ds = [f1 f2] [e1 e2]^-1, e1, e2 the solid edges: f1 = dX/dxi1, f2 = dX/dxi2
  affine_value.x = image[0];
  set_jacobian(f1, f2, affine_value);
  affine_det = det2(affine_value.jac);
  if (!(affine_det > 0)) throw Error("the map flattens " + name());
}

double MappedTriangle::magnitude() const {
  double m = 0;
  for (const Point& p : image) m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
  return m;
}

double MappedTriangle::extent(Point f1, Point f2) {
  return std::max({std::fabs(f1.x), std::fabs(f1.y), std::fabs(f2.x), std::fabs(f2.y), std::fabs(f2.x - f1.x),
                   std::fabs(f2.y - f1.y)});
}

double MappedTriangle::area_round_off(long pieces) const {
  double perimeter = 0;  // at most sqrt(2) times the perimeter: a bound suffices
  for (int i = 0; i < 3; ++i) perimeter += std::fabs(image[(i + 1) % 3].x - image[i].x) + std::fabs(image[(i + 1) % 3].y - image[i].y);
  return 8 * kEps * magnitude() * perimeter * static_cast<double>(pieces + 2);
}

}  // namespace dlmfsi
