// How fully symmetric tetrahedron rules of high degree can be found (not part of the build). The nodes and weights
// of fully symmetric orbits solve the moment equations of an orthonormal (Dubiner) basis of the polynomials of
// degree <= d on the tetrahedron; the equations reduce by symmetry to the invariant ones. Random starts are
// improved by Levenberg-Marquardt in double with an analytic jacobian, through a parametrization that keeps every
// point in the closed tetrahedron and every weight nonnegative (w = t^2, barycentric coordinates = squares of the
// coordinates of a point on a unit sphere); converged starts are polished by damped Gauss-Newton in __float128 on
// the orbit parameters themselves, kept when every weight is positive and every point strictly inside, and
// verified on every monomial x^i y^j z^k, i + j + k <= d, of the reference tetrahedron (0,0,0), (1,0,0), (0,1,0),
// (0,0,1) against i! j! k! / (i + j + k + 3)!, both in __float128 and in long double.
//   g++ -O2 -std=c++17 tests/reference/tet_rules_symmetric.cpp -o /tmp/tet_rules_symmetric -lquadmath
//   /tmp/tet_rules_symmetric D S4 S31 S22 S211 S1111 [TRIES] [SEED] [MINBARY] [KICKS]
// with the orbits in barycentric coordinates (l0, l1, l2, l3), points (x, y, z) = (l1, l2, l3): S4 (0 or 1) the
// centroid, S31 of (a, a, a, 1 - 3a), S22 of (a, a, 1/2 - a, 1/2 - a), S211 of (a, a, b, 1 - 2a - b), S1111 of
// (a, b, c, 1 - a - b - c). The weights sum to 1 (integral over a tetrahedron of volume V = V sum w_i f(x_i)). A
// structure needs at least as many unknowns (S4 + 2 S31 + 2 S22 + 3 S211 + 4 S1111) as invariant moment
// conditions, the number of (i, j, k) with 2i + 3j + 4k <= d (printed). The first start (of TRIES, default 2000,
// random generator seeded with SEED, default 1) that gives a valid rule whose barycentric coordinates all exceed
// MINBARY (default 0) is printed, with 25 significant digits, and the search stops. Unlike on the triangle, plain
// random starts mostly stall (orbits whose weight or barycentric coordinate reaches 0 sit at a stationary point of
// the squared parametrization): with KICKS > 0 (default 0), a stalled search gives its dead orbits (or one random
// orbit) fresh random parameters and goes on, at most KICKS times per start. Progress goes to stderr. The rules
// came from (points; structure S4 S31 S22 S211 S1111; about 1 s to 3 min each on one core)
//   10 1 4 1 4 1 400 1 (95)                11 1 4 1 4 2 2000 1 0 10 (119)       12 1 5 1 6 2 300 1 (147)
//   13 1 5 1 6 3 2000 1 0 10 (171)         14 1 6 2 8 4 2000 1 0 10 (229)       15 1 6 2 9 5 2000 1 0 10 (265)
//   16 1 7 2 11 7 2000 1 0 10 (341)        17 1 8 2 12 8 2000 1 0 10 (381)
// (the collapsed Gauss-Jacobi products have 216, 216, 343, 343, 512, 512, 729 and 729 points). Every weight is
// positive and every point strictly inside; the largest relative monomial residual is below 2.1e-18 in long
// double (below 6e-33 in __float128). Also valid: 16 1 7 2 10 7 2000 1 0 10 (329 points, but its smallest
// barycentric coordinate is 3.3e-8) and 17 1 8 3 13 9 2000 1 0 10 (423). Not found: 10 1 4 1 4 0 (71 points, 300
// starts), 10 1 5 0 5 0 (81; 300 starts without kicks, 100 with 30 kicks), 17 1 7 2 10 8 (353; ~50 starts without
// kicks, ~15 with 10 kicks), 17 1 7 2 11 8 (365; ~10 starts with 10 kicks, 3 min).
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

// A value and its gradient in (x, y, z).
template <class T>
struct Dual {
  T v, dx, dy, dz;
};
template <class T>
Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) {
  return {a.v * b.v, a.dx * b.v + a.v * b.dx, a.dy * b.v + a.v * b.dy, a.dz * b.v + a.v * b.dz};
}
template <class T>
Dual<T> operator*(T s, const Dual<T>& a) {
  return {s * a.v, s * a.dx, s * a.dy, s * a.dz};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) {
  return {a.v - b.v, a.dx - b.dx, a.dy - b.dy, a.dz - b.dz};
}
template <class T>
Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) {
  return {a.v + b.v, a.dx + b.dx, a.dy + b.dy, a.dz + b.dz};
}

// The Jacobi polynomials P_n^(alpha,0)(s / v) v^n, n = 0..count-1, homogeneous in (s, v), without division by v.
template <class T>
void jacobi(int count, T alpha, const Dual<T>& s, const Dual<T>& v, std::vector<Dual<T>>& out) {
  out.clear();
  if (count <= 0) return;
  out.push_back({1, 0, 0, 0});
  if (count == 1) return;
  out.push_back(T(0.5) * (T(alpha + 2) * s + alpha * v));
  const Dual<T> v2 = v * v;
  for (int n = 2; n < count; ++n) {
    const T c = 2 * n + alpha;
    const T f = 2 * n * (n + alpha) * (c - 2);
    out.push_back((T(1) / f) * ((c - 1) * ((T(c * (c - 2)) * s + (alpha * alpha) * v) * out[n - 1]) -
                                T(2 * (n + alpha - 1) * (n - 1) * c) * (v2 * out[n - 2])));
  }
}

// The orthonormal basis of the polynomials of degree <= d on the reference tetrahedron for the mean (the integral
// divided by the volume): phi_ijk = sqrt((2i+1)(2i+2j+2)(2i+2j+2k+3)/6) P_i(a) ((1-b)/2)^i P_j^(2i+1,0)(b)
// ((1-c)/2)^(i+j) P_k^(2i+2j+2,0)(c), a = 2x/(1-y-z) - 1, b = 2y/(1-z) - 1, c = 2z - 1, computed without
// division: P_i(a) ((1-b)/2)^i ((1-c)/2)^i = P_i(s1 / u1) u1^i with s1 = 2x+y+z-1, u1 = 1-y-z, and
// P_j(b) ((1-c)/2)^j = P_j(s2 / u2) u2^j with s2 = 2y+z-1, u2 = 1-z.
template <class T>
void basis(int d, T x, T y, T z, std::vector<Dual<T>>& phi) {
  phi.clear();
  const Dual<T> one{1, 0, 0, 0}, s1{2 * x + y + z - 1, 2, 1, 1}, u1{1 - y - z, 0, -1, -1};
  const Dual<T> s2{2 * y + z - 1, 0, 2, 1}, u2{1 - z, 0, 0, -1}, c{2 * z - 1, 0, 0, 2};
  std::vector<Dual<T>> pi, pj, pk;
  jacobi<T>(d + 1, 0, s1, u1, pi);
  for (int i = 0; i <= d; ++i) {
    jacobi<T>(d - i + 1, T(2 * i + 1), s2, u2, pj);
    for (int j = 0; i + j <= d; ++j) {
      jacobi<T>(d - i - j + 1, T(2 * i + 2 * j + 2), c, one, pk);
      const Dual<T> f = pi[i] * pj[j];
      for (int k = 0; i + j + k <= d; ++k)
        phi.push_back(root(T((2 * i + 1) * (2 * i + 2 * j + 2) * (2 * i + 2 * j + 2 * k + 3)) / T(6)) * (f * pk[k]));
    }
  }
}

// The orbit kinds: S4, S31, S22, S211, S1111, with their position parameter counts and points.
const int kParams[5] = {0, 1, 1, 2, 3};
const int kPoints[5] = {1, 4, 6, 12, 24};
const char* const kNames[5] = {"S4", "S31", "S22", "S211", "S1111"};
// The label pattern of each kind (barycentric coordinate l_m is the value of label pattern[m]).
const int kPattern[5][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 1, 1}, {0, 0, 1, 2}, {0, 1, 2, 3}};

// The label values of an orbit and their derivatives by its parameters p (value = v0 + sum_p p dv[p]).
template <class T>
void labels(int kind, const T* p, T value[4], T dv[3][4]) {
  for (int q = 0; q < 3; ++q)
    for (int m = 0; m < 4; ++m) dv[q][m] = 0;
  if (kind == 0) value[0] = T(1) / 4;
  if (kind == 1) {
    value[0] = p[0], value[1] = 1 - 3 * p[0];
    dv[0][0] = 1, dv[0][1] = -3;
  }
  if (kind == 2) {
    value[0] = p[0], value[1] = T(1) / 2 - p[0];
    dv[0][0] = 1, dv[0][1] = -1;
  }
  if (kind == 3) {
    value[0] = p[0], value[1] = p[1], value[2] = 1 - 2 * p[0] - p[1];
    dv[0][0] = 1, dv[0][2] = -2, dv[1][1] = 1, dv[1][2] = -1;
  }
  if (kind == 4) {
    value[0] = p[0], value[1] = p[1], value[2] = p[2], value[3] = 1 - p[0] - p[1] - p[2];
    dv[0][0] = 1, dv[0][3] = -1, dv[1][1] = 1, dv[1][3] = -1, dv[2][2] = 1, dv[2][3] = -1;
  }
}

// One point of a rule: barycentric coordinates, weight, the derivatives of (x, y, z) = (l1, l2, l3) by the
// orbit's parameters, and the orbit.
template <class T>
struct Node {
  T l[4], w;
  T d[3][3];  // d[q][0..2]: d(x, y, z) / d parameter q
  int orbit;
};

struct Structure {
  int degree;
  int count[5];
  std::vector<int> kinds, firsts;  // per orbit
  int unknowns = 0, points = 0;
  Structure(int d, const int* c) : degree(d) {
    for (int k = 0; k < 5; ++k) {
      count[k] = c[k];
      for (int i = 0; i < c[k]; ++i) {
        kinds.push_back(k);
        firsts.push_back(unknowns);
        unknowns += kParams[k] + 1;
        points += kPoints[k];
      }
    }
  }
  int orbits() const { return static_cast<int>(kinds.size()); }
  int equations() const { return (degree + 1) * (degree + 2) * (degree + 3) / 6; }
  int weightIndex(int o) const { return firsts[o] + kParams[kinds[o]]; }
  int conditions() const {
    int n = 0;
    for (int i = 0; 2 * i <= degree; ++i)
      for (int j = 0; 2 * i + 3 * j <= degree; ++j)
        for (int k = 0; 2 * i + 3 * j + 4 * k <= degree; ++k) ++n;
    return n;
  }
};

// The points of the rule with orbit parameters u (per orbit: position parameters, then weight).
template <class T>
std::vector<Node<T>> nodes(const Structure& st, const std::vector<T>& u) {
  std::vector<Node<T>> out;
  for (int o = 0; o < st.orbits(); ++o) {
    const int kind = st.kinds[o], i = st.firsts[o];
    T value[4], dv[3][4];
    labels<T>(kind, u.data() + i, value, dv);
    int pattern[4] = {kPattern[kind][0], kPattern[kind][1], kPattern[kind][2], kPattern[kind][3]};
    do {
      Node<T> q;
      q.w = u[st.weightIndex(o)];
      q.orbit = o;
      for (int m = 0; m < 4; ++m) q.l[m] = value[pattern[m]];
      for (int p = 0; p < 3; ++p)
        for (int m = 0; m < 3; ++m) q.d[p][m] = dv[p][pattern[m + 1]];
      out.push_back(q);
    } while (std::next_permutation(pattern, pattern + 4));
  }
  return out;
}

// The moment residuals r_k = sum_i w_i phi_k(x_i) - delta_k0 and their jacobian (row-major, equations x unknowns)
// in the orbit parameters.
template <class T>
void moments(const Structure& st, const std::vector<T>& u, std::vector<T>& r, std::vector<T>* jac) {
  const int m = st.equations(), n = st.unknowns;
  r.assign(m, 0);
  r[0] = -1;
  if (jac) jac->assign(static_cast<size_t>(m) * n, 0);
  std::vector<Dual<T>> phi;
  for (const Node<T>& q : nodes(st, u)) {
    basis(st.degree, q.l[1], q.l[2], q.l[3], phi);
    const int i = st.firsts[q.orbit], np = kParams[st.kinds[q.orbit]], iw = i + np;
    for (int k = 0; k < m; ++k) {
      r[k] += q.w * phi[k].v;
      if (!jac) continue;
      T* row = jac->data() + static_cast<size_t>(k) * n;
      row[iw] += phi[k].v;
      for (int p = 0; p < np; ++p)
        row[i + p] += q.w * (phi[k].dx * q.d[p][0] + phi[k].dy * q.d[p][1] + phi[k].dz * q.d[p][2]);
    }
  }
}


// The squares y_0..y_m of the coordinates of the point of the unit sphere with angles t_0..t_{m-1}
// (y_0 = cos^2 t_0, y_1 = sin^2 t_0 cos^2 t_1, ..., y_m = sin^2 t_0 ... sin^2 t_{m-1}), summing to 1, and
// dy[i][j] = dy_i / dt_j.
void sphere(int m, const double* t, double y[4], double dy[4][3]) {
  double prefix = 1;  // product of sin^2 so far
  for (int i = 0; i <= m; ++i) {
    const double c2 = i < m ? std::cos(t[i]) * std::cos(t[i]) : 1;
    y[i] = prefix * c2;
    for (int j = 0; j < m; ++j) {
      if (j > i) {
        dy[i][j] = 0;
        continue;
      }
      const double s = std::sin(t[j]), c = std::cos(t[j]);
      // y_i = (prod_{l<i} sin^2 t_l) cos^2 t_i; d/dt_j of sin^2 = 2sc, of cos^2 = -2sc
      if (j < i) dy[i][j] = s * s > 0 ? y[i] * 2 * c / s : 0;
      else dy[i][j] = prefix * (-2 * s * c);
    }
    if (i < m) prefix *= std::sin(t[i]) * std::sin(t[i]);
  }
}

// The search parametrization: weights t^2; S31 a = y_1 / 3, S22 a = y_1 / 2 (of a circle point), S211
// (a, b) = (y_1 / 2, y_2), S1111 (a, b, c) = (y_1, y_2, y_3) (of a sphere point). Gives u(t) and du/dt per orbit
// (du[i][q] for position unknown i of the orbit by angle q of the same orbit, 3 entries per unknown).
void natural(const Structure& st, const std::vector<double>& t, std::vector<double>& u, std::vector<double>& du) {
  const int n = st.unknowns;
  u.assign(n, 0);
  du.assign(3 * static_cast<size_t>(n), 0);
  for (int o = 0; o < st.orbits(); ++o) {
    const int kind = st.kinds[o], i = st.firsts[o], np = kParams[kind], iw = i + np;
    u[iw] = t[iw] * t[iw];
    du[3 * iw] = 2 * t[iw];
    if (np == 0) continue;
    double y[4], dy[4][3];
    sphere(np, t.data() + i, y, dy);
    const double scale[5][3] = {{0, 0, 0}, {1.0 / 3, 0, 0}, {0.5, 0, 0}, {0.5, 1, 0}, {1, 1, 1}};
    for (int p = 0; p < np; ++p) {
      u[i + p] = scale[kind][p] * y[p + 1];
      for (int q = 0; q < np; ++q) du[3 * (i + p) + q] = scale[kind][p] * dy[p + 1][q];
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
  const int m = st.equations(), n = st.unknowns;
  jac->assign(ju.size(), 0);
  for (int o = 0; o < st.orbits(); ++o) {
    const int i = st.firsts[o], np = kParams[st.kinds[o]], iw = i + np;
    for (int e = 0; e < m; ++e) {
      const double* a = ju.data() + static_cast<size_t>(e) * n;
      double* b = jac->data() + static_cast<size_t>(e) * n;
      b[iw] = a[iw] * du[3 * iw];
      for (int q = 0; q < np; ++q) {
        double s = 0;
        for (int p = 0; p < np; ++p) s += a[i + p] * du[3 * (i + p) + q];
        b[i + q] = s;
      }
    }
  }
}

// Levenberg-Marquardt in the search parameters from t; returns the final sum of squares.
double search(const Structure& st, std::vector<double>& t, int iterations) {
  const auto residual = [&st](const std::vector<double>& v, std::vector<double>& r, std::vector<double>* jac) {
    searchMoments(st, v, r, jac);
  };
  return rule_search::levenberg_marquardt(st.unknowns, residual, t, iterations);
}

// Gauss-Newton in __float128 on the orbit parameters, lightly damped (the structure may have more unknowns than
// independent conditions); returns the final sum of squares.
Quad polish(const Structure& st, std::vector<Quad>& u) {
  const auto residual = [&st](const std::vector<Quad>& v, std::vector<Quad>& r, std::vector<Quad>* jac) {
    moments<Quad>(st, v, r, jac);
  };
  return rule_search::gauss_newton(st.unknowns, residual, u, 12);
}

using rule_search::factorial;

// The largest relative error of the rule on the monomials x^i y^j z^k, i + j + k <= d, of the reference
// tetrahedron, whose mean is 6 i! j! k! / (i + j + k + 3)!.
template <class T>
T monomialError(const Structure& st, const std::vector<T>& u) {
  const int d = st.degree, e = d + 1;
  std::vector<T> sum(static_cast<size_t>(e) * e * e, 0), px(e), py(e), pz(e);
  for (const Node<T>& q : nodes(st, u)) {
    px[0] = py[0] = pz[0] = 1;
    for (int i = 1; i <= d; ++i) {
      px[i] = px[i - 1] * q.l[1];
      py[i] = py[i - 1] * q.l[2];
      pz[i] = pz[i - 1] * q.l[3];
    }
    for (int i = 0; i <= d; ++i)
      for (int j = 0; i + j <= d; ++j)
        for (int k = 0; i + j + k <= d; ++k) sum[(i * e + j) * e + k] += q.w * px[i] * py[j] * pz[k];
  }
  T worst = 0;
  for (int i = 0; i <= d; ++i)
    for (int j = 0; i + j <= d; ++j)
      for (int k = 0; i + j + k <= d; ++k) {
        const T exact = 6 * factorial<T>(i) * factorial<T>(j) * factorial<T>(k) / factorial<T>(i + j + k + 3);
        worst = std::max(worst, magnitude((sum[(i * e + j) * e + k] - exact) / exact));
      }
  return worst;
}

using rule_search::text;

// Prints the rule, its residuals, smallest weight and smallest barycentric coordinate.
void report(const Structure& st, const std::vector<Quad>& u, int attempt, unsigned seed) {
  std::vector<long double> ul(u.begin(), u.end());
  Quad minWeight = 1, minBary = 1, sum = 0;
  for (const Node<Quad>& q : nodes(st, u)) {
    minWeight = std::min(minWeight, q.w);
    sum += q.w;
    for (Quad l : q.l) minBary = std::min(minBary, l);
  }
  const int* c = st.count;
  std::printf("degree %d, %d points, structure S4 %d S31 %d S22 %d S211 %d S1111 %d (args %d %d %d %d %d %d, "
              "seed %u, start %d)\n", st.degree, st.points, c[0], c[1], c[2], c[3], c[4], st.degree, c[0], c[1],
              c[2], c[3], c[4], seed, attempt);
  std::printf("  max relative monomial residual: __float128 %.3Le, long double %.3Le\n",
              static_cast<long double>(monomialError<Quad>(st, u)), monomialError<long double>(st, ul));
  std::printf("  min weight %.6Le, min barycentric coordinate %.6Le, weight sum - 1 %.3Le\n",
              static_cast<long double>(minWeight), static_cast<long double>(minBary),
              static_cast<long double>(sum - 1));
  const char* names[3] = {"a", "b", "c"};
  for (int o = 0; o < st.orbits(); ++o) {
    const int kind = st.kinds[o], i = st.firsts[o];
    std::string line = "  " + std::string(kNames[kind]);
    for (int p = 0; p < kParams[kind]; ++p) line += std::string("  ") + names[p] + " " + text(u[i + p]);
    line += "  w " + text(u[st.weightIndex(o)]);
    std::printf("%s\n", line.c_str());
  }
  std::fflush(stdout);
}

// A random start: points uniform in the tetrahedron (orbit parameters uniform on their ranges), weights near
// 1 / points.
std::vector<double> start(const Structure& st, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<double> t(st.unknowns);
  const double w0 = 1.0 / st.points;
  for (int o = 0; o < st.orbits(); ++o) {
    const int kind = st.kinds[o], i = st.firsts[o], np = kParams[kind];
    t[i + np] = std::sqrt(w0 * (0.5 + uniform(rng)));
    // uniform point of the simplex of dimension np via sorted uniforms, then angles with those squares
    std::vector<double> cut(np);
    for (double& v : cut) v = uniform(rng);
    std::sort(cut.begin(), cut.end());
    double y[4], prev = 0;
    for (int p = 0; p < np; ++p) y[p] = cut[p] - prev, prev = cut[p];
    if (np > 0) y[np] = 1 - prev;
    double rest = 1;  // y_0 = cos^2 t_0, y_1 = sin^2 t_0 cos^2 t_1, ...
    for (int p = 0; p < np; ++p) {
      const double c2 = rest > 0 ? std::min(1.0, y[p] / rest) : 1;
      t[i + p] = std::acos(std::sqrt(c2));
      rest -= y[p];
    }
  }
  return t;
}

// Levenberg-Marquardt from a random start; whenever it stalls, the orbits that died (weight below a fifth of the
// mean point weight, or a barycentric coordinate below 0.002; else one random orbit) get fresh random parameters
// and the search goes on, KICKS times at most. Returns the final sum of squares.
double searchWithKicks(const Structure& st, std::vector<double>& t, std::mt19937_64& rng, int kicks) {
  double f = search(st, t, 600);
  for (int kick = 0; kick < kicks && !(f < 1e-20); ++kick) {
    std::vector<double> u, du;
    natural(st, t, u, du);
    std::vector<double> minBary(st.orbits(), 1);
    for (const Node<double>& q : nodes(st, u))
      for (double l : q.l) minBary[q.orbit] = std::min(minBary[q.orbit], l);
    const std::vector<double> fresh = start(st, rng);
    std::vector<int> dead;
    for (int o = 0; o < st.orbits(); ++o)
      if (u[st.weightIndex(o)] < 0.2 / st.points || minBary[o] < 0.002) dead.push_back(o);
    if (dead.empty()) dead.push_back(static_cast<int>(rng() % st.orbits()));
    for (int o : dead)
      for (int p = st.firsts[o]; p <= st.weightIndex(o); ++p) t[p] = fresh[p];
    f = search(st, t, 600);
  }
  return f;
}

bool valid(const Structure& st, const std::vector<Quad>& u, Quad minBary) {
  return rule_search::positive_inside(nodes(st, u), minBary);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: %s D S4 S31 S22 S211 S1111 [TRIES] [SEED] [MINBARY] [KICKS]\n", argv[0]);
    return 2;
  }
  int counts[5];
  for (int k = 0; k < 5; ++k) counts[k] = std::atoi(argv[2 + k]);
  const Structure st(std::atoi(argv[1]), counts);
  const int tries = argc > 7 ? std::atoi(argv[7]) : 2000;
  const unsigned seed = argc > 8 ? static_cast<unsigned>(std::atoi(argv[8])) : 1u;
  const Quad minBary = argc > 9 ? std::atof(argv[9]) : 0;
  const int kicks = argc > 10 ? std::atoi(argv[10]) : 0;
  std::printf("degree %d: %d points, %d unknowns, %d invariant conditions\n", st.degree, st.points, st.unknowns,
              st.conditions());
  std::fflush(stdout);
  std::mt19937_64 rng(seed);
  int converged = 0;
  for (int attempt = 0; attempt < tries; ++attempt) {
    if (attempt % 10 == 0) std::fprintf(stderr, "start %d, %d converged so far\n", attempt, converged);
    std::vector<double> t = start(st, rng), ud, du;
    if (!(searchWithKicks(st, t, rng, kicks) < 1e-20)) continue;
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
