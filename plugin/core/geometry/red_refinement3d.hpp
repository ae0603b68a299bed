// The reference tetrahedron {(0,0,0), (1,0,0), (0,1,0), (0,0,1)} refined by the red rule.
#pragma once
#include <array>
#include <vector>

#include "point3.hpp"

namespace dlmfsi {

// The reference tetrahedron refined `level` times (0 <= level <= 4) by the red rule: each tetrahedron into
// its four corner tetrahedra and the four of its inner octahedron (split along one diagonal), 8^level
// positively oriented tetrahedra of equal volume that tile it.
const std::vector<std::array<Point3, 4>>& reference_subdivision(int level);

}  // namespace dlmfsi
