#include "fe/basis.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dlmfsi {

namespace {

// Segments chosen inside the reference element, away from its vertices and from symmetry lines.
template <int D>
struct ProbeSegments;
template <>
struct ProbeSegments<2> {
  static constexpr int count = 3;
  static Point at(int i, double t) {
    const Point ends[3][2] = {{{0.05, 0.11}, {0.83, 0.07}}, {{0.13, 0.79}, {0.21, 0.04}}, {{0.71, 0.2}, {0.06, 0.37}}};
    return {ends[i][0].x + t * (ends[i][1].x - ends[i][0].x), ends[i][0].y + t * (ends[i][1].y - ends[i][0].y)};
  }
};
template <>
struct ProbeSegments<3> {
  static constexpr int count = 4;
  static Point3 at(int i, double t) {
    const Point3 ends[4][2] = {{{0.05, 0.11, 0.07}, {0.71, 0.07, 0.13}},
                               {{0.13, 0.69, 0.04}, {0.21, 0.04, 0.62}},
                               {{0.61, 0.2, 0.09}, {0.06, 0.17, 0.37}},
                               {{0.03, 0.08, 0.77}, {0.33, 0.41, 0.05}}};
    return ends[i][0] + t * (ends[i][1] - ends[i][0]);
  }
};

}  // namespace

template <int D>
int polynomial_degree(const BasisOf<D>& basis, const std::vector<int>& components, int k) {
  constexpr int kMaxDegree = 12, kSamples = kMaxDegree + 2, kSlots = D + 1;
  const int width = basis.local_dofs() * basis.components() * kSlots;
  std::vector<double> samples(static_cast<size_t>(kSamples) * width);
  int degree = 0;
  for (int seg = 0; seg < ProbeSegments<D>::count; ++seg) {
    for (int s = 0; s < kSamples; ++s) {
      const double t = static_cast<double>(s) / (kSamples - 1);
      basis.evaluate(k, ProbeSegments<D>::at(seg, t), &samples[static_cast<size_t>(s) * width]);
    }
    for (int f = 0; f < width; f += kSlots) {  // values only
      const int comp = (f / kSlots) % basis.components();
      if (!components.empty() && std::find(components.begin(), components.end(), comp) == components.end()) continue;
      std::vector<double> d(kSamples);
      double scale = 0;
      for (int s = 0; s < kSamples; ++s) {
        d[s] = samples[static_cast<size_t>(s) * width + f];
        scale = std::max(scale, std::fabs(d[s]));
      }
      if (scale == 0) continue;
      // After m differencing passes d[0 .. kSamples-m) holds the m-th differences; the degree is the
      // largest m - 1 with non-zero m-th differences. 2^m bounds their growth from round-off.
      int deg = -1;
      for (int m = 1; m < kSamples; ++m) {
        double big = 0;
        for (int s = 0; s + m < kSamples; ++s) {
          d[s] = d[s + 1] - d[s];
          big = std::max(big, std::fabs(d[s]));
        }
        if (big <= 1e-9 * scale * std::ldexp(1.0, m)) {
          deg = m - 1;
          break;
        }
      }
      if (deg < 0) return -1;
      degree = std::max(degree, deg);
    }
  }
  return degree;
}

template int polynomial_degree<2>(const BasisOf<2>&, const std::vector<int>&, int);
template int polynomial_degree<3>(const BasisOf<3>&, const std::vector<int>&, int);

}  // namespace dlmfsi
