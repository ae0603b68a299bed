#include "rules.hpp"

#include <cmath>
#include <mutex>
#include <utility>

#include "errors.hpp"

namespace dlmfsi {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence (n >= 1, |x| < 1).
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1);
}

}  // namespace

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(n, 0);
  weights.assign(n, 0);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev-like first guess.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5)), p, dp;
    for (int it = 0; it < 100; ++it) {
      legendre(n, x, p, dp);
      const double dx = p / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    legendre(n, x, p, dp);  // the derivative at the converged node, for the weight 2 / ((1 - x^2) P_n'^2)
    nodes[i] = 0.5 * (1 - x);
    weights[i] = 1.0 / ((1 - x * x) * dp * dp);  // half of the [-1,1] weight
  }
}

namespace {

// The symmetric orbits of a point in barycentric coordinates: (a, a, 1-2a) gives 3 points, (a, b, c) 6.
void orbit3(std::vector<RulePoint>& r, double a, double w) {
  r.push_back({{a, a}, w});
  r.push_back({{1 - 2 * a, a}, w});
  r.push_back({{a, 1 - 2 * a}, w});
}

void orbit6(std::vector<RulePoint>& r, double a, double b, double w) {
  const double c = 1 - a - b;
  for (auto [u, v] : {std::pair{a, b}, std::pair{b, a}, std::pair{a, c}, std::pair{c, a}, std::pair{b, c}, std::pair{c, b}})
    r.push_back({{u, v}, w});
}

std::vector<RulePoint> make_rule(int degree) {
  std::vector<RulePoint> r;
  if (degree <= 1) {
    r.push_back({{1.0 / 3, 1.0 / 3}, 1.0});
  } else if (degree == 2) {
    orbit3(r, 1.0 / 6, 1.0 / 3);
  } else if (degree == 4) {  // Dunavant
    orbit3(r, 0.445948490915965, 0.223381589678011);
    orbit3(r, 0.091576213509771, 0.109951743655322);
  } else if (degree == 5) {  // Radon
    const double s = std::sqrt(15.0);
    r.push_back({{1.0 / 3, 1.0 / 3}, 9.0 / 40});
    orbit3(r, (6 - s) / 21, (155 - s) / 1200);
    orbit3(r, (6 + s) / 21, (155 + s) / 1200);
  } else if (degree == 6) {  // Dunavant
    orbit3(r, 0.249286745170910, 0.116786275726379);
    orbit3(r, 0.063089014491502, 0.050844906370207);
    orbit6(r, 0.310352451033784, 0.053145049844817, 0.082851075618374);
  } else if (degree == 8) {  // Dunavant
    r.push_back({{1.0 / 3, 1.0 / 3}, 0.144315607677787});
    orbit3(r, 0.459292588292723, 0.095091634267285);
    orbit3(r, 0.170569307751760, 0.103217370534718);
    orbit3(r, 0.050547228317031, 0.032458497623198);
    orbit6(r, 0.263112829634638, 0.008394777409958, 0.027230314174435);
  } else {
    std::vector<double> xu, wu, xv, wv;
    gauss_legendre((degree + 3) / 2, xu, wu);
    gauss_legendre((degree + 2) / 2, xv, wv);
    for (size_t i = 0; i < xu.size(); ++i)
      for (size_t j = 0; j < xv.size(); ++j)
        r.push_back({{xu[i], (1 - xu[i]) * xv[j]}, 2 * wu[i] * wv[j] * (1 - xu[i])});
  }
  return r;
}

}  // namespace

const std::vector<RulePoint>& triangle_rule(int degree) {
  constexpr int kMax = 60;
  if (degree < 0 || degree > kMax) throw Error("quadrature degree " + std::to_string(degree) + " outside [0, 60]");
  static std::vector<RulePoint> rules[kMax + 1];
  static std::once_flag once;
  std::call_once(once, [] {
    for (int d = 0; d <= kMax; ++d) rules[d] = make_rule(d);
  });
  return rules[degree];
}

}  // namespace dlmfsi
