#include "mesh/fluid_search3d.hpp"

#include <algorithm>
#include <cmath>

namespace dlmfsi {

// About one tetrahedron per cell, cells roughly cubic, of side (volume / nt)^(1/3) (clamped as doubles:
// converting a double beyond the int range is undefined behaviour).
void Tetrahedra::cells_per_axis(int nt, const double w[3], int n[3]) {
  // (w0 w1 w2 / nt)^(1/3), each factor's root taken first: the product itself under- or overflows for
  // meshes beyond about 1e-100..1e100 in size.
  const double side = std::cbrt(w[0]) * std::cbrt(w[1]) * std::cbrt(w[2]) / std::cbrt(static_cast<double>(nt));
  for (int a = 0; a < 3; ++a) n[a] = static_cast<int>(std::max(1.0, std::min(1024.0, w[a] / side)));
}

int Tetrahedra::max_walk_steps(int n) { return 64 + 8 * static_cast<int>(std::cbrt(static_cast<double>(n))); }

template class FluidGridOf<Tetrahedra>;
template class FluidSearchOf<Tetrahedra>;

}  // namespace dlmfsi
