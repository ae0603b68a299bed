#include "basis.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dlmfsi {

int polynomial_degree(const Basis& basis, const std::vector<int>& components, int k) {
  constexpr int kMaxDegree = 12, kSamples = kMaxDegree + 2;
  const int width = basis.local_dofs() * basis.components() * 3;
  // Segments chosen inside the reference triangle, away from its vertices and from symmetry lines.
  const Point ends[3][2] = {{{0.05, 0.11}, {0.83, 0.07}}, {{0.13, 0.79}, {0.21, 0.04}}, {{0.71, 0.2}, {0.06, 0.37}}};
  std::vector<double> samples(static_cast<size_t>(kSamples) * width);
  int degree = 0;
  for (const auto& seg : ends) {
    for (int s = 0; s < kSamples; ++s) {
      const double t = static_cast<double>(s) / (kSamples - 1);
      basis.evaluate(k, {seg[0].x + t * (seg[1].x - seg[0].x), seg[0].y + t * (seg[1].y - seg[0].y)},
                     &samples[static_cast<size_t>(s) * width]);
    }
    for (int f = 0; f < width; f += 3) {  // values only
      const int comp = (f / 3) % basis.components();
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

}  // namespace dlmfsi
