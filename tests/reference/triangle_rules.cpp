// How fully symmetric triangle rules of high degree can be found (not part of the build). The nodes and weights of
// fully symmetric orbits solve the moment equations of an orthonormal (Dubiner) basis of the polynomials of degree
// <= d; the equations of the non-invariant basis functions hold by symmetry. Random starts are improved by
// Levenberg-Marquardt in double with an analytic jacobian, through a parametrization that keeps every point in the
// closed triangle and every weight nonnegative (w = t^2, bary = squared sines and cosines); converged starts are
// polished by damped Gauss-Newton in __float128 on the orbit parameters themselves, kept when every weight is
// positive and every point strictly inside, and verified on every monomial x^i y^j, i + j <= d, of the reference
// triangle (0,0), (1,0), (0,1) against i! j! / (i + j + 2)!, both in __float128 and in long double.
//   g++ -O2 -std=c++17 tests/reference/triangle_rules.cpp -o /tmp/triangle_rules -lquadmath
//   /tmp/triangle_rules D CENTROID N21 N111 [TRIES] [SEED] [MINBARY]
// with the orbits in barycentric coordinates: CENTROID (0 or 1) of (1/3, 1/3, 1/3), N21 of (a, a, 1 - 2a), N111 of
// (a, b, 1 - a - b). The weights sum to 1 (integral over a triangle of area A = A sum w_i f(x_i)). A structure needs
// at least as many unknowns (CENTROID + 2 N21 + 3 N111) as invariant moment conditions, the number of (i, j) with
// 2i + 3j <= d: 14, 19, 24, 30, 37 and 44 for d = 10, 12, 14, 16, 18 and 20. The first start (of TRIES, default
// 2000, random generator seeded with SEED, default 1) that gives a valid rule whose barycentric coordinates all
// exceed MINBARY (default 0) is printed, with 25 significant digits, and the search stops. The rules came from
//   10 1 2 3 200 1 (25 points)     12 0 5 3 2000 1 (33)    14 0 6 4 2000 1 (42)    16 1 4 7 3000 1 (55)
//   18 1 6 8 3000 1 (67)           18 1 6 8 20000 1 0.001 (67, smallest barycentric coordinate 3.8e-3 for 5.5e-4)
//   20 1 8 9 3000 1 (79)
// each within a few seconds (degree 18 and 20: 15 s; the second degree 18 rule: 1 min). Smaller structures with
// enough unknowns were not found within 90 to 200 s each: 12 1 6 2, 12 1 8 1, 12 0 8 1 (31 and 30 points),
// 14 1 7 3, 14 0 9 2 (40, 39), 16 1 7 5, 16 0 6 6, 16 0 8 5 (52, 54, 54), 18 0 8 7, 18 1 9 6 (66, 64),
// 20 0 10 8, 20 1 11 7 (78, 76), nor 14 0 6 4 with every barycentric coordinate above 0.005.
#include <quadmath.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "rule_search.hpp"

namespace {

using rule_search::magnitude;
using rule_search::Quad;
using rule_search::root;

// A value and its gradient in (x, y).
template <class T>
struct Dual {
  T v, dx, dy;
};
template <class T>
Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) {
  return {a.v * b.v, a.dx * b.v + a.v * b.dx, a.dy * b.v + a.v * b.dy};
}
template <class T>
Dual<T> operator*(T s, const Dual<T>& a) {
  return {s * a.v, s * a.dx, s * a.dy};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) {
  return {a.v - b.v, a.dx - b.dx, a.dy - b.dy};
}
template <class T>
Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) {
  return {a.v + b.v, a.dx + b.dx, a.dy + b.dy};
}

// The orthonormal basis of the polynomials of degree <= d on the reference triangle for the mean (the integral
// over the triangle divided by its area): phi_ij = sqrt((2i+1)(i+j+1)) L_i(a) ((1-b)/2)^i P_j^(2i+1,0)(b), with
// a = 2x/(1-y) - 1 and b = 2y - 1, and L_i(a) ((1-b)/2)^i computed without division.
template <class T>
void basis(int d, T x, T y, std::vector<Dual<T>>& phi) {
  phi.clear();
  const Dual<T> one{1, 0, 0}, s{2 * x + y - 1, 2, 1}, u{1 - y, 0, -1}, b{2 * y - 1, 0, 2};
  const Dual<T> u2 = u * u;
  Dual<T> q0 = one, q1 = s;  // L_i(a) ((1-b)/2)^i for i and i + 1
  for (int i = 0; i <= d; ++i) {
    const T alpha = 2 * i + 1;
    Dual<T> p0 = one, p1 = T(0.5) * (T(alpha + 2) * b + Dual<T>{alpha, 0, 0});
    for (int j = 0; i + j <= d; ++j) {
      phi.push_back(root(T((2 * i + 1) * (i + j + 1))) * (q0 * p0));
      const int n = j + 2;  // P_n^(alpha,0) from P_{n-1} and P_{n-2}
      const T c = 2 * n + alpha;
      const T f = 2 * n * (n + alpha) * (c - 2);
      const Dual<T> p2 = (T(1) / f) * ((c - 1) * (T(c * (c - 2)) * b + Dual<T>{alpha * alpha, 0, 0}) * p1 -
                                        T(2 * (n + alpha - 1) * (n - 1) * c) * p0);
      p0 = p1;
      p1 = p2;
    }
    const Dual<T> q2 = (T(2 * i + 3) / T(i + 2)) * (s * q1) - (T(i + 1) / T(i + 2)) * (u2 * q0);
    q0 = q1;
    q1 = q2;
  }
}

// One point of a rule: barycentric coordinates, weight, and the derivatives of (x, y) = (l1, l2) by the orbit's
// first and second parameters.
template <class T>
struct Node {
  T l[3], w;
  T dxa, dya, dxb, dyb;
  int orbit;
};

struct Structure {
  int degree, centroid, n21, n111;
  int unknowns() const { return centroid + 2 * n21 + 3 * n111; }
  int points() const { return centroid + 3 * n21 + 6 * n111; }
  int equations() const { return (degree + 1) * (degree + 2) / 2; }
  int orbits() const { return centroid + n21 + n111; }
  // The index of the first unknown of orbit k, and its kind (3 centroid, 21, 111).
  int first(int k) const {
    if (k < centroid) return 0;
    k -= centroid;
    if (k < n21) return centroid + 2 * k;
    return centroid + 2 * n21 + 3 * (k - n21);
  }
  int kind(int k) const { return k < centroid ? 3 : k < centroid + n21 ? 21 : 111; }
};

// The points of the rule with orbit parameters u: centroid (w), S21 (a, w), S111 (a, b, w).
template <class T>
std::vector<Node<T>> nodes(const Structure& st, const std::vector<T>& u) {
  static const int perm3[3][3] = {{0, 1, 2}, {0, 2, 1}, {2, 0, 1}};
  static const int perm6[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<Node<T>> p;
  for (int k = 0; k < st.orbits(); ++k) {
    const int i = st.first(k), kind = st.kind(k);
    if (kind == 3) {
      const T third = T(1) / 3;
      p.push_back({{third, third, third}, u[i], 0, 0, 0, 0, k});
      continue;
    }
    const T a = u[i], b = kind == 21 ? a : u[i + 1], w = u[i + (kind == 21 ? 1 : 2)];
    const T v[3] = {a, b, 1 - a - b};
    const T da[3] = {1, T(kind == 21 ? 1 : 0), T(kind == 21 ? -2 : -1)}, db[3] = {0, 1, -1};
    const int count = kind == 21 ? 3 : 6;
    for (int m = 0; m < count; ++m) {
      const int* q = kind == 21 ? perm3[m] : perm6[m];
      p.push_back({{v[q[0]], v[q[1]], v[q[2]]}, w, da[q[1]], da[q[2]], db[q[1]], db[q[2]], k});
    }
  }
  return p;
}

// The moment residuals r_k = sum_i w_i phi_k(x_i) - delta_k0 and their jacobian (row-major, equations x unknowns)
// in the orbit parameters.
template <class T>
void moments(const Structure& st, const std::vector<T>& u, std::vector<T>& r, std::vector<T>* jac) {
  const int m = st.equations(), n = st.unknowns();
  r.assign(m, 0);
  r[0] = -1;
  if (jac) jac->assign(static_cast<size_t>(m) * n, 0);
  std::vector<Dual<T>> phi;
  for (const Node<T>& q : nodes(st, u)) {
    basis(st.degree, q.l[1], q.l[2], phi);
    const int i = st.first(q.orbit), kind = st.kind(q.orbit);
    const int iw = i + (kind == 3 ? 0 : kind == 21 ? 1 : 2);
    for (int k = 0; k < m; ++k) {
      r[k] += q.w * phi[k].v;
      if (!jac) continue;
      T* row = jac->data() + static_cast<size_t>(k) * n;
      row[iw] += phi[k].v;
      if (kind == 3) continue;
      row[i] += q.w * (phi[k].dx * q.dxa + phi[k].dy * q.dya);
      if (kind == 111) row[i + 1] += q.w * (phi[k].dx * q.dxb + phi[k].dy * q.dyb);
    }
  }
}


// The search parametrization: weights t^2, S21 a = sin^2(t) / 2, S111 (a, b) = sin^2(t1) (cos^2(t2), sin^2(t2)).
// Gives u(t) and the derivatives du/dt (each unknown of u depends on the t of its own orbit only: stored as
// du[i * 2 + 0/1] for the (up to two) position parameters, by t[first], t[first + 1]).
void natural(const Structure& st, const std::vector<double>& t, std::vector<double>& u, std::vector<double>& du) {
  const int n = st.unknowns();
  u.assign(n, 0);
  du.assign(2 * static_cast<size_t>(n), 0);
  for (int k = 0; k < st.orbits(); ++k) {
    const int i = st.first(k), kind = st.kind(k);
    const int iw = i + (kind == 3 ? 0 : kind == 21 ? 1 : 2);
    u[iw] = t[iw] * t[iw];
    du[2 * iw] = 2 * t[iw];
    if (kind == 21) {
      const double s = std::sin(t[i]), c = std::cos(t[i]);
      u[i] = s * s / 2;
      du[2 * i] = s * c;
    } else if (kind == 111) {
      const double s1 = std::sin(t[i]), c1 = std::cos(t[i]), s2 = std::sin(t[i + 1]), c2 = std::cos(t[i + 1]);
      u[i] = s1 * s1 * c2 * c2;
      u[i + 1] = s1 * s1 * s2 * s2;
      du[2 * i] = 2 * s1 * c1 * c2 * c2;         // da/dt1
      du[2 * i + 1] = -2 * s1 * s1 * s2 * c2;    // da/dt2
      du[2 * (i + 1)] = 2 * s1 * c1 * s2 * s2;   // db/dt1
      du[2 * (i + 1) + 1] = 2 * s1 * s1 * s2 * c2;  // db/dt2
    }
  }
}

// The residuals and the jacobian in the search parameters t.
void searchMoments(const Structure& st, const std::vector<double>& t, std::vector<double>& r,
                   std::vector<double>* jac) {
  std::vector<double> u, du;
  natural(st, t, u, du);
  if (!jac) return moments<double>(st, u, r, nullptr);
  std::vector<double> ju;
  moments<double>(st, u, r, &ju);
  const int m = st.equations(), n = st.unknowns();
  jac->assign(ju.size(), 0);
  for (int k = 0; k < st.orbits(); ++k) {
    const int i = st.first(k), kind = st.kind(k);
    const int iw = i + (kind == 3 ? 0 : kind == 21 ? 1 : 2);
    for (int e = 0; e < m; ++e) {
      const double* a = ju.data() + static_cast<size_t>(e) * n;
      double* b = jac->data() + static_cast<size_t>(e) * n;
      b[iw] = a[iw] * du[2 * iw];
      if (kind == 21) b[i] = a[i] * du[2 * i];
      if (kind == 111) {
        b[i] = a[i] * du[2 * i] + a[i + 1] * du[2 * (i + 1)];
        b[i + 1] = a[i] * du[2 * i + 1] + a[i + 1] * du[2 * (i + 1) + 1];
      }
    }
  }
}

// Levenberg-Marquardt in the search parameters from t; returns the final sum of squares.
double search(const Structure& st, std::vector<double>& t, int iterations) {
  const auto residual = [&st](const std::vector<double>& v, std::vector<double>& r, std::vector<double>* jac) {
    searchMoments(st, v, r, jac);
  };
  return rule_search::levenberg_marquardt(st.unknowns(), residual, t, iterations);
}

// Gauss-Newton in __float128 on the orbit parameters, lightly damped (the structure may have more unknowns than
// independent conditions); returns the final sum of squares.
Quad polish(const Structure& st, std::vector<Quad>& u) {
  const auto residual = [&st](const std::vector<Quad>& v, std::vector<Quad>& r, std::vector<Quad>* jac) {
    moments<Quad>(st, v, r, jac);
  };
  return rule_search::gauss_newton(st.unknowns(), residual, u, 30);
}

using rule_search::factorial;

// The largest relative error of the rule on the monomials x^i y^j, i + j <= d, of the reference triangle, whose
// mean is 2 i! j! / (i + j + 2)!.
template <class T>
T monomialError(const Structure& st, const std::vector<T>& u) {
  const int d = st.degree;
  std::vector<T> sum(static_cast<size_t>(d + 1) * (d + 1), 0), px(d + 1), py(d + 1);
  for (const Node<T>& q : nodes(st, u)) {
    px[0] = py[0] = 1;
    for (int i = 1; i <= d; ++i) {
      px[i] = px[i - 1] * q.l[1];
      py[i] = py[i - 1] * q.l[2];
    }
    for (int i = 0; i <= d; ++i)
      for (int j = 0; i + j <= d; ++j) sum[i * (d + 1) + j] += q.w * px[i] * py[j];
  }
  T worst = 0;
  for (int i = 0; i <= d; ++i)
    for (int j = 0; i + j <= d; ++j) {
      const T exact = 2 * factorial<T>(i) * factorial<T>(j) / factorial<T>(i + j + 2);
      worst = std::max(worst, magnitude((sum[i * (d + 1) + j] - exact) / exact));
    }
  return worst;
}

using rule_search::text;

// Prints the rule, its residuals, smallest weight and smallest barycentric coordinate.
void report(const Structure& st, const std::vector<Quad>& u, int attempt, unsigned seed) {
  std::vector<long double> ul(u.begin(), u.end());
  Quad minWeight = 1, minBary = 1;
  for (const Node<Quad>& q : nodes(st, u)) {
    minWeight = std::min(minWeight, q.w);
    for (Quad l : q.l) minBary = std::min(minBary, l);
  }
  std::printf("degree %d, %d points, structure centroid %d S21 %d S111 %d (args %d %d %d %d, seed %u, start %d)\n",
              st.degree, st.points(), st.centroid, st.n21, st.n111, st.degree, st.centroid, st.n21, st.n111, seed,
              attempt);
  std::printf("  max relative monomial residual: __float128 %.3Le, long double %.3Le\n",
              static_cast<long double>(monomialError<Quad>(st, u)), monomialError<long double>(st, ul));
  std::printf("  min weight %.6Le, min barycentric coordinate %.6Le\n", static_cast<long double>(minWeight),
              static_cast<long double>(minBary));
  for (int k = 0; k < st.orbits(); ++k) {
    const int i = st.first(k), kind = st.kind(k);
    if (kind == 3) std::printf("  S3   w %s\n", text(u[i]).c_str());
    if (kind == 21) std::printf("  S21  a %s  w %s\n", text(u[i]).c_str(), text(u[i + 1]).c_str());
    if (kind == 111)
      std::printf("  S111 a %s  b %s  w %s\n", text(u[i]).c_str(), text(u[i + 1]).c_str(), text(u[i + 2]).c_str());
  }
}

// A random start: points uniform in the triangle (S21 a uniform in (0, 1/2)), weights near 1 / points.
std::vector<double> start(const Structure& st, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<double> t(st.unknowns());
  const double w0 = 1.0 / st.points();
  for (int k = 0; k < st.orbits(); ++k) {
    const int i = st.first(k), kind = st.kind(k);
    const int iw = i + (kind == 3 ? 0 : kind == 21 ? 1 : 2);
    t[iw] = std::sqrt(w0 * (0.5 + uniform(rng)));
    if (kind == 21) t[i] = std::asin(std::sqrt(uniform(rng)));
    if (kind == 111) {
      double x = uniform(rng), y = uniform(rng);
      if (x + y > 1) x = 1 - x, y = 1 - y;
      const double c = 1 - x - y;
      t[i] = std::acos(std::sqrt(c));
      t[i + 1] = std::atan2(std::sqrt(y), std::sqrt(x));
    }
  }
  return t;
}

bool valid(const Structure& st, const std::vector<Quad>& u, Quad minBary) {
  return rule_search::positive_inside(nodes(st, u), minBary);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s D CENTROID N21 N111 [TRIES] [SEED] [MINBARY]\n", argv[0]);
    return 2;
  }
  const Structure st{std::atoi(argv[1]), std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4])};
  const int tries = argc > 5 ? std::atoi(argv[5]) : 2000;
  const unsigned seed = argc > 6 ? static_cast<unsigned>(std::atoi(argv[6])) : 1u;
  const Quad minBary = argc > 7 ? std::atof(argv[7]) : 0;
  std::mt19937_64 rng(seed);
  int converged = 0;
  for (int attempt = 0; attempt < tries; ++attempt) {
    std::vector<double> t = start(st, rng), ud, du;
    if (!(search(st, t, 600) < 1e-20)) continue;
    ++converged;
    natural(st, t, ud, du);
    std::vector<Quad> u(ud.begin(), ud.end());
    if (!(polish(st, u) < Quad(1e-60)) || !valid(st, u, minBary)) continue;
    report(st, u, attempt, seed);
    return 0;
  }
  std::printf("not found: %d converged starts of %d\n", converged, tries);
  return 1;
}
