// A dot product along the points of a piece, summed fast and in a fixed order.
#pragma once

namespace dlmfsi {

// sum_p w[p] row[p], in four interleaved partial sums (one running sum would wait on each addition).
inline double weighted_sum(const double* w, const double* row, int n) {
  double s[4] = {0, 0, 0, 0};
  int p = 0;
  for (; p + 4 <= n; p += 4)
    for (int i = 0; i < 4; ++i) s[i] += w[p + i] * row[p + i];
  for (; p < n; ++p) s[0] += w[p] * row[p];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

}  // namespace dlmfsi
