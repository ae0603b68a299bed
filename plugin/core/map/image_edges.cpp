#include "map/image_edges.hpp"

#include <algorithm>
#include <cmath>

namespace dlmfsi {

namespace {

double binomial(int n, int k) {
  double b = 1;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

}  // namespace

void ImageEdges::set(const TriangleMap& map) {
  degree = map.degree();
  const PolynomialMapCoefficients& c = map.coefficients();
  auto coefficient_of = [&](int a, int b) {
    const int m = (a + b) * (a + b + 1) / 2 + b;
    return Point{c.x[2 * m], c.x[2 * m + 1]};
  };
  // Along edge i, xi1 = p1 + t q1 and xi2 = p2 + t q2: xi1^a xi2^b expanded by the binomial theorem.
  for (int i = 0; i < 3; ++i) {
    const Point p = start(i), q = direction(i);
    for (int k = 0; k <= degree; ++k) coefficient[i][k] = {0, 0};
    for (int total = 1; total <= degree; ++total)
      for (int b = 0; b <= total; ++b) {
        const int a = total - b;
        const Point cm = coefficient_of(a, b);
        if (cm.x == 0 && cm.y == 0) continue;
        for (int j = 0; j <= a; ++j)
          for (int l = 0; l <= b; ++l) {
            const double f = binomial(a, j) * binomial(b, l) * std::pow(p.x, a - j) * std::pow(q.x, j) *
                             std::pow(p.y, b - l) * std::pow(q.y, l);
            if (f != 0) coefficient[i][j + l] = coefficient[i][j + l] + f * cm;
          }
      }
  }
  // On [0, 1]: t^i = sum_{k >= i} C(k, i) / C(d, i) B_k(t), so control point k is sum_{i <= k} C(k, i) / C(d, i) c_i.
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k <= degree; ++k) {
      Point b{0, 0};
      for (int l = 0; l <= k; ++l) b = b + (binomial(k, l) / binomial(degree, l)) * coefficient[i][l];
      control[i][k] = b;
      edge_lo[i] = k == 0 ? b : Point{std::min(edge_lo[i].x, b.x), std::min(edge_lo[i].y, b.y)};
      edge_hi[i] = k == 0 ? b : Point{std::max(edge_hi[i].x, b.x), std::max(edge_hi[i].y, b.y)};
    }
  // Bernstein coefficients on T (barycentric lambda0 = 1 - xi1 - xi2, lambda1 = xi1, lambda2 = xi2), degree
  // d: beta_JK = sum_{a <= J, b <= K} c_ab C(J, a) C(K, b) / (d! / (a! b! (d - a - b)!)).
  const int d = degree;
  lo = hi = Point{0, 0};
  for (int J = 0; J <= d; ++J)
    for (int K = 0; J + K <= d; ++K) {
      Point beta{0, 0};
      for (int a = 0; a <= J; ++a)
        for (int b = 0; b <= K; ++b) {
          if (a + b == 0) continue;  // the constant term is 0
          const double multinomial = binomial(d, a) * binomial(d - a, b);
          beta = beta + (binomial(J, a) * binomial(K, b) / multinomial) * coefficient_of(a, b);
        }
      lo = {std::min(lo.x, beta.x), std::min(lo.y, beta.y)};
      hi = {std::max(hi.x, beta.x), std::max(hi.y, beta.y)};
    }
}

}  // namespace dlmfsi
