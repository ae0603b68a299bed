// The median of a benchmark's timings (the mean of the two middle ones for an even count).
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
