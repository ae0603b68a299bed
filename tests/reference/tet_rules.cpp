// How fe/rules.cpp's symmetric tetrahedron rules of degree 6 to 9 were found (not part of the build): nodes and
// weights of fully symmetric orbits, solved by Levenberg-Marquardt on the moment equations of every monomial
// x^a y^b z^c, a + b + c <= d, from random starts, in long double; a start counts when its relative residual falls
// below 1e-15 with every weight positive and every point inside the tetrahedron.
//   g++ -O2 -std=c++17 tests/reference/tet_rules.cpp -o /tmp/tet_rules
//   /tmp/tet_rules D CENTROID N4 N6 N12 [TRIES] [SEED]
// with the orbits in barycentric coordinates: CENTROID (0 or 1), N4 of (a, a, a, 1 - 3a), N6 of
// (a, a, 1/2 - a, 1/2 - a), N12 of (a, a, b, 1 - 2a - b). The rules in fe/rules.cpp came from
//   6 0 3 0 1 300 1     7 1 1 1 2 5000 1     8 0 4 1 2 20000 5     9 1 4 1 3 20000 7
// (24, 35, 46 and 59 points). Rules3d tests them, exact to their degree and not beyond.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "rule_search.hpp"

namespace {

using Real = long double;

struct Point {
  Real l[4];  // barycentric coordinates
  Real w;
};

struct Problem {
  int degree, centroid, n4, n6, n12;
  std::vector<std::array<int, 3>> monomials;
  std::vector<Real> exact;  // 6 int_T x^a y^b z^c: the weights sum to 1

  int unknowns() const { return centroid + 2 * n4 + 2 * n6 + 3 * n12; }
  int points() const { return centroid + 4 * n4 + 6 * n6 + 12 * n12; }

  // The distinct permutations of (l0, l1, l2, l3), each with weight w.
  static void orbit(std::vector<Point>& p, Real l0, Real l1, Real l2, Real l3, Real w) {
    std::array<Real, 4> l = {l0, l1, l2, l3};
    std::sort(l.begin(), l.end());
    do p.push_back({{l[0], l[1], l[2], l[3]}, w});
    while (std::next_permutation(l.begin(), l.end()));
  }

  std::vector<Point> rule(const std::vector<Real>& u) const {
    std::vector<Point> p;
    int k = 0;
    if (centroid) p.push_back({{0.25L, 0.25L, 0.25L, 0.25L}, u[k++]});
    for (int i = 0; i < n4; ++i, k += 2) orbit(p, u[k], u[k], u[k], 1 - 3 * u[k], u[k + 1]);
    for (int i = 0; i < n6; ++i, k += 2) orbit(p, u[k], u[k], 0.5L - u[k], 0.5L - u[k], u[k + 1]);
    for (int i = 0; i < n12; ++i, k += 3) orbit(p, u[k], u[k], u[k + 1], 1 - 2 * u[k] - u[k + 1], u[k + 2]);
    return p;
  }

  // The moment equations' relative residuals.
  std::vector<Real> residual(const std::vector<Real>& u) const {
    std::vector<Real> sum(monomials.size(), 0);
    for (const Point& q : rule(u)) {
      Real px[64], py[64], pz[64];
      px[0] = py[0] = pz[0] = 1;
      for (int i = 1; i <= degree; ++i) {
        px[i] = px[i - 1] * q.l[1];
        py[i] = py[i - 1] * q.l[2];
        pz[i] = pz[i - 1] * q.l[3];
      }
      for (size_t m = 0; m < monomials.size(); ++m)
        sum[m] += q.w * px[monomials[m][0]] * py[monomials[m][1]] * pz[monomials[m][2]];
    }
    for (size_t m = 0; m < monomials.size(); ++m) sum[m] = (sum[m] - exact[m]) / exact[m];
    return sum;
  }

  bool valid(const std::vector<Real>& u) const {
    return rule_search::positive_inside(rule(u), 0);
  }
};

using rule_search::solve;
using rule_search::squares;
using rule_search::factorial;

// Levenberg-Marquardt from u (central-difference jacobian); returns the final sum of squares.
Real minimise(const Problem& pb, std::vector<Real>& u) {
  const int n = pb.unknowns();
  std::vector<Real> r = pb.residual(u);
  Real f = squares(r), lambda = 1e-3L;
  const int m = static_cast<int>(r.size());
  for (int it = 0; it < 300 && f > 1e-34L; ++it) {
    std::vector<Real> jac(static_cast<size_t>(m) * n);
    for (int k = 0; k < n; ++k) {
      const Real h = 1e-9L;
      std::vector<Real> up = u, down = u;
      up[k] += h;
      down[k] -= h;
      const std::vector<Real> rp = pb.residual(up), rd = pb.residual(down);
      for (int i = 0; i < m; ++i) jac[static_cast<size_t>(i) * n + k] = (rp[i] - rd[i]) / (2 * h);
    }
    bool improved = false;
    for (int tries = 0; tries < 20 && !improved; ++tries) {
      std::vector<Real> a(static_cast<size_t>(n) * n, 0), step(n, 0);
      for (int i = 0; i < m; ++i)
        for (int p = 0; p < n; ++p) {
          step[p] -= jac[static_cast<size_t>(i) * n + p] * r[i];
          for (int q = 0; q < n; ++q) a[p * n + q] += jac[static_cast<size_t>(i) * n + p] * jac[static_cast<size_t>(i) * n + q];
        }
      for (int p = 0; p < n; ++p) a[p * n + p] *= 1 + lambda;
      if (!solve(a, step, n)) {
        lambda *= 10;
        continue;
      }
      std::vector<Real> v = u;
      for (int p = 0; p < n; ++p) v[p] += step[p];
      const std::vector<Real> rv = pb.residual(v);
      const Real fv = squares(rv);
      if (fv < f) {
        u = v;
        r = rv;
        f = fv;
        lambda = std::max(lambda / 10, Real(1e-12L));
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved || (it == 60 && f > 1e-6L)) break;  // stuck, or a hopeless start
  }
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s D CENTROID N4 N6 N12 [TRIES] [SEED]\n", argv[0]);
    return 2;
  }
  Problem pb{std::atoi(argv[1]), std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]), std::atoi(argv[5]), {}, {}};
  const int tries = argc > 6 ? std::atoi(argv[6]) : 2000;
  const unsigned seed = argc > 7 ? static_cast<unsigned>(std::atoi(argv[7])) : 1u;
  for (int t = 0; t <= pb.degree; ++t)
    for (int a = 0; a <= t; ++a)
      for (int b = 0; a + b <= t; ++b) {
        const int c = t - a - b;
        pb.monomials.push_back({a, b, c});
        pb.exact.push_back(6 * factorial<Real>(a) * factorial<Real>(b) * factorial<Real>(c) /
                           factorial<Real>(t + 3));
      }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  const Real w0 = Real(1) / pb.points();
  for (int attempt = 0; attempt < tries; ++attempt) {
    std::vector<Real> u;
    if (pb.centroid) u.push_back(w0);
    for (int i = 0; i < pb.n4; ++i) u.insert(u.end(), {Real(uniform(rng) / 3), w0});
    for (int i = 0; i < pb.n6; ++i) u.insert(u.end(), {Real(uniform(rng) / 2), w0});
    for (int i = 0; i < pb.n12; ++i) {
      const Real a = uniform(rng) / 2, b = uniform(rng) * (1 - 2 * a);
      u.insert(u.end(), {a, b, w0});
    }
    const Real f = minimise(pb, u);
    if (!(f < 1e-30L) || !pb.valid(u)) continue;
    std::printf("degree %d, %d points, start %d, relative residual %.3Le\n", pb.degree, pb.points(), attempt,
                std::sqrt(f));
    int k = 0;
    if (pb.centroid) std::printf("  centroid %.20Lg\n", u[k++]);
    for (int i = 0; i < pb.n4; ++i, k += 2) std::printf("  four %.20Lg %.20Lg\n", u[k], u[k + 1]);
    for (int i = 0; i < pb.n6; ++i, k += 2) std::printf("  six %.20Lg %.20Lg\n", u[k], u[k + 1]);
    for (int i = 0; i < pb.n12; ++i, k += 3) std::printf("  twelve %.20Lg %.20Lg %.20Lg\n", u[k], u[k + 1], u[k + 2]);
    return 0;
  }
  std::printf("not found\n");
  return 1;
}
