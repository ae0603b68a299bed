#include "geometry/red_refinement3d.hpp"

#include <utility>

#include "geometry/predicates3d.hpp"

namespace dlmfsi {

const std::vector<std::array<Point3, 4>>& reference_subdivision(int level) {
  using Tet = std::array<Point3, 4>;
  static const auto table = [] {
    std::vector<std::vector<Tet>> all(5);
    all[0] = {Tet{Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0, 0, 1}}};
    for (int l = 1; l < 5; ++l)
      for (const Tet& t : all[l - 1]) {
        auto mid = [&](int i, int j) { return 0.5 * (t[i] + t[j]); };
        const Point3 m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3), m23 = mid(2, 3);
        const Tet children[8] = {{t[0], m01, m02, m03}, {m01, t[1], m12, m13}, {m02, m12, t[2], m23},
                                 {m03, m13, m23, t[3]}, {m01, m02, m03, m13}, {m01, m02, m12, m13},
                                 {m02, m03, m13, m23}, {m02, m12, m13, m23}};
        for (Tet c : children) {
          if (volume6(c[0], c[1], c[2], c[3]) < 0) std::swap(c[2], c[3]);
          all[l].push_back(c);
        }
      }
    return all;
  }();
  return table[level];
}

}  // namespace dlmfsi
