#include "mesh/fluid_search.hpp"

#include <algorithm>
#include <cmath>

namespace dlmfsi {

// About one triangle per cell, cells roughly square: n_x n_y = nt with n_x / n_y = w_x / w_y (clamped as
// doubles: converting a double beyond the int range is undefined behaviour).
void Triangles::cells_per_axis(int nt, const double w[2], int n[2]) {
  n[0] = static_cast<int>(std::max(1.0, std::min(4096.0, std::sqrt(nt * w[0] / w[1]))));
  n[1] = static_cast<int>(std::max(1.0, std::min(4096.0, std::sqrt(nt * w[1] / w[0]))));
}

int Triangles::max_walk_steps(int n) { return 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(n))); }

template class FluidGridOf<Triangles>;
template class FluidSearchOf<Triangles>;

}  // namespace dlmfsi
