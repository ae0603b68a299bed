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

// out[a * nb + b] = sum_p x[a][p] y[b][p] for a < na, b < nb: the products of two sets of rows along the
// points, in blocks of 2 x 4 rows whose eight sums run side by side (each point's six values loaded once for
// eight products, where a sum at a time loads two for one), each sum in two lanes (even and odd points: GCC
// and Clang vector extensions, one SSE2 register on x86-64) added at the end; the rows left over by the blocks
// as weighted_sum. The order of the additions is fixed: the same sums bit for bit on every run.
inline void row_products(const double* const* x, int na, const double* const* y, int nb, int n, double* out) {
  typedef double Pair __attribute__((vector_size(16)));
  auto load = [](const double* p) {
    Pair v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
  };
  int a = 0;
  for (; a + 2 <= na; a += 2) {
    int b = 0;
    for (; b + 4 <= nb; b += 4) {
      const double *x0 = x[a], *x1 = x[a + 1], *y0 = y[b], *y1 = y[b + 1], *y2 = y[b + 2], *y3 = y[b + 3];
      Pair s00 = {0, 0}, s01 = s00, s02 = s00, s03 = s00, s10 = s00, s11 = s00, s12 = s00, s13 = s00;
      int p = 0;
      for (; p + 2 <= n; p += 2) {
        const Pair u = load(x0 + p), v = load(x1 + p), c0 = load(y0 + p), c1 = load(y1 + p), c2 = load(y2 + p),
                   c3 = load(y3 + p);
        s00 += u * c0;
        s01 += u * c1;
        s02 += u * c2;
        s03 += u * c3;
        s10 += v * c0;
        s11 += v * c1;
        s12 += v * c2;
        s13 += v * c3;
      }
      double t[8] = {s00[0] + s00[1], s01[0] + s01[1], s02[0] + s02[1], s03[0] + s03[1],
                     s10[0] + s10[1], s11[0] + s11[1], s12[0] + s12[1], s13[0] + s13[1]};
      if (p < n) {  // the odd point left
        const double u = x0[p], v = x1[p], c[4] = {y0[p], y1[p], y2[p], y3[p]};
        for (int j = 0; j < 4; ++j) {
          t[j] += u * c[j];
          t[4 + j] += v * c[j];
        }
      }
      double* o0 = out + static_cast<long>(a) * nb + b;
      double* o1 = o0 + nb;
      for (int j = 0; j < 4; ++j) {
        o0[j] = t[j];
        o1[j] = t[4 + j];
      }
    }
    for (; b < nb; ++b) {
      out[static_cast<long>(a) * nb + b] = weighted_sum(x[a], y[b], n);
      out[static_cast<long>(a + 1) * nb + b] = weighted_sum(x[a + 1], y[b], n);
    }
  }
  for (; a < na; ++a)
    for (int b = 0; b < nb; ++b) out[static_cast<long>(a) * nb + b] = weighted_sum(x[a], y[b], n);
}

}  // namespace dlmfsi
