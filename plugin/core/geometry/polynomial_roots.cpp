#include "geometry/polynomial_roots.hpp"

#include <cmath>

namespace dlmfsi {

double polynomial_value(const double* c, int degree, double t) {
  double v = c[degree];
  for (int k = degree - 1; k >= 0; --k) v = v * t + c[k];
  return v;
}

namespace {

// The root of p in [a, b] where p(a) and p(b) have opposite signs (neither 0) and p is monotone: Newton's
// steps kept inside the bracket (a bisection where a step would leave it), the bracket shrunk at every
// evaluation, until a step is below the last bits of t or the bracket has no double between its ends.
double bisect(const double* c, int degree, double a, double b, double pa) {
  double t = 0.5 * (a + b);
  for (int it = 0; it < 200; ++it) {
    double p = c[degree], dp = 0;
    for (int k = degree - 1; k >= 0; --k) {
      dp = dp * t + p;
      p = p * t + c[k];
    }
    if (p == 0) return t;
    if ((p < 0) == (pa < 0)) {
      a = t;
      pa = p;
    } else {
      b = t;
    }
    double next = dp != 0 ? t - p / dp : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (!(next > a && next < b)) return next;  // no double left between the bracket's ends
    if (std::fabs(next - t) <= 2e-16 * std::fabs(t)) return next;
    t = next;
  }
  return t;
}

}  // namespace

int roots_in(const double* c, int degree, double lo, double hi, double p_lo, double p_hi, double* roots) {
  while (degree > 0 && c[degree] == 0) --degree;
  if (degree == 0) return 0;
  // The ends of the monotone parts: lo, the roots of p' inside, hi.
  double ends[kMaxRootsDegree + 2], values[kMaxRootsDegree + 2];
  int n = 0;
  ends[n] = lo;
  values[n++] = p_lo;
  if (degree >= 2) {
    double dc[kMaxRootsDegree];
    for (int k = 1; k <= degree; ++k) dc[k - 1] = k * c[k];
    double critical[kMaxRootsDegree];
    const int nc = roots_in(dc, degree - 1, lo, hi, polynomial_value(dc, degree - 1, lo),
                            polynomial_value(dc, degree - 1, hi), critical);
    for (int i = 0; i < nc; ++i) {
      if (!(critical[i] > ends[n - 1] && critical[i] < hi)) continue;
      ends[n] = critical[i];
      values[n++] = polynomial_value(c, degree, critical[i]);
    }
  }
  ends[n] = hi;
  values[n++] = p_hi;
  int count = 0;
  auto add = [&](double t) {
    if (count < degree && (count == 0 || t > roots[count - 1])) roots[count++] = t;
  };
  if (values[0] == 0) add(lo);
  for (int i = 0; i + 1 < n; ++i) {
    const double a = values[i], b = values[i + 1];
    if (b == 0) {
      // a zero at a critical point is a tangency unless the sign changes across it
      if (i + 1 == n - 1 || (i + 2 < n && (values[i + 2] < 0) != (a < 0) && a != 0)) add(ends[i + 1]);
      continue;
    }
    if (a != 0 && (a < 0) != (b < 0)) add(bisect(c, degree, ends[i], ends[i + 1], a));
  }
  return count;
}

}  // namespace dlmfsi
