#include "sides/scale.hpp"

#include <algorithm>

#include "fe/lattice.hpp"

namespace dlmfsi {

int scale_exponent(const Mesh& mesh) {
  double largest = 0;
  for (const Point& p : mesh.vertices) largest = std::max({largest, std::fabs(p.x), std::fabs(p.y)});
  if (!(largest > 0) || !std::isfinite(largest) || (largest >= 0x1p-64 && largest <= 0x1p64)) return 0;
  int e;
  std::frexp(largest, &e);  // largest = f 2^e, f in [0.5, 1)
  return e;
}

Mesh scaled(Mesh mesh, int e) {
  if (e != 0)
    for (Point& p : mesh.vertices) p = {std::ldexp(p.x, -e), std::ldexp(p.y, -e)};
  return mesh;
}

bool ScaledMap::coefficients(int k, double* cx, double* cy) const {
  if (!base_.coefficients(k, cx, cy)) return false;
  if (factor_ != 1) {
    const int n = monomial_count(degree_);
    for (int m = 0; m < n; ++m) {
      cx[m] *= factor_;
      cy[m] *= factor_;
    }
  }
  return true;
}

}  // namespace dlmfsi
