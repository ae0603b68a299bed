#include "integration/conic_region.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace dlmfsi {

namespace {

using Complex = std::complex<double>;

// The roots of a x^2 + b x + c strictly inside (lo, hi), ascending, in the forms without cancellation; their count.
int roots_inside(double a, double b, double c, double lo, double hi, double (&root)[2]) {
  double x[2];
  int k = 0;
  if (a == 0) {
    if (b != 0) x[k++] = -c / b;
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      if (h != 0) {
        x[k++] = h / a;
        x[k++] = c / h;
      } else {
        x[k++] = 0;  // b = 0 and c = 0: a double root at 0
      }
    }
  }
  int n = 0;
  for (int i = 0; i < k; ++i)
    if (x[i] > lo && x[i] < hi) root[n++] = x[i];
  if (n == 2 && root[0] > root[1]) std::swap(root[0], root[1]);
  return n;
}

// rho of the Bernstein ellipse (foci -1 and 1) through x: Gauss-Legendre on [-1, 1] converges like rho^-2n for a
// function analytic inside it. Its semi-axes a and b: 2 a = |x - 1| + |x + 1| and a^2 - b^2 = 1, rho = a + b.
double ellipse(Complex x) {
  const double re = x.real(), im2 = x.imag() * x.imag();
  const double a = 0.5 * (std::sqrt((re - 1) * (re - 1) + im2) + std::sqrt((re + 1) * (re + 1) + im2));
  return a + std::sqrt(std::max(0.0, (a - 1) * (a + 1)));
}

struct Breakpoint {
  double s;
  bool tangent;
};

class ConicRegion {
 public:
  static constexpr int kMax = 64;  // polygon vertices

  ConicRegion(const double (*polygon)[2], int m, const Quadratic2& q, int sign, const LineRule& outer,
              const LineRule& inner, int degree, std::vector<RegionPoint2>& out)
      : m_(std::min(m, kMax)), sign_(sign), degree_(degree), outer_(outer), inner_(inner), out_(out) {
    frame(polygon, q);
  }
  void run();

 private:
  void frame(const double (*polygon)[2], const Quadratic2& q);
  // The outer breakpoints and the tangents along t; false where sign q <= 0 on the whole polygon.
  bool breakpoints(int& n);
  void interval(double from, double to, int depth);
  const LineRule& short_rule(double h, double scale, double rho) const;
  // the chord of the polygon along t at s (strictly between its ends), and the inner points on it
  void line(double at, double ws);

  int m_, sign_, degree_;
  const LineRule &outer_, &inner_;
  std::vector<RegionPoint2>& out_;
  double cu_ = 0, cv_ = 0, su_, sv_, tu_, tv_;  // centroid, and the axes s, t in (u, v)
  Quadratic2 r_;                               // q in (s, t) about the centroid
  double s_[kMax], t_[kMax], smin_ = HUGE_VAL, smax_ = -HUGE_VAL;
  Breakpoint cuts_[3 * kMax + 4];
  Complex singular_[2];  // the curve's tangents along t, real or complex
  int n_singular_ = 0;
  double rho_min_ = 0;
};

// t along grad q at the centroid (the curve crosses the inner lines rather than runs along them), s across it.
void ConicRegion::frame(const double (*polygon)[2], const Quadratic2& q) {
  for (int i = 0; i < m_; ++i) {
    cu_ += polygon[i][0];
    cv_ += polygon[i][1];
  }
  cu_ /= m_;
  cv_ /= m_;
  const double gu = q.cu + 2 * q.cuu * cu_ + q.cuv * cv_, gv = q.cv + q.cuv * cu_ + 2 * q.cvv * cv_;
  const double gl = std::hypot(gu, gv);
  tu_ = gl > 0 ? gu / gl : 0;
  tv_ = gl > 0 ? gv / gl : 1;
  su_ = tv_;
  sv_ = -tu_;
  auto hessian = [&q](double au, double av, double bu, double bv) {
    return 2 * q.cuu * au * bu + q.cuv * (au * bv + av * bu) + 2 * q.cvv * av * bv;
  };
  r_.c0 = q.at(cu_, cv_);
  r_.cu = gu * su_ + gv * sv_;
  r_.cv = gu * tu_ + gv * tv_;
  r_.cuu = 0.5 * hessian(su_, sv_, su_, sv_);
  r_.cuv = hessian(su_, sv_, tu_, tv_);
  r_.cvv = 0.5 * hessian(tu_, tv_, tu_, tv_);
  for (int i = 0; i < m_; ++i) {
    const double du = polygon[i][0] - cu_, dv = polygon[i][1] - cv_;
    s_[i] = du * su_ + dv * sv_;
    t_[i] = du * tu_ + dv * tv_;
    smin_ = std::min(smin_, s_[i]);
    smax_ = std::max(smax_, s_[i]);
  }
}

// The inner integral is analytic in s between breakpoints: the polygon's vertices where sign q >= 0 (a vertex where
// sign q < 0 bounds no part of the region: near it the region ends on q = 0, not on the polygon's edges), where q = 0
// crosses an edge, and the real tangents along t (q = dq/dt = 0) inside.
bool ConicRegion::breakpoints(int& n) {
  n = 0;
  bool inside = false;
  double value[kMax], scale = 0;
  for (int i = 0; i < m_; ++i) {
    value[i] = sign_ * r_.at(s_[i], t_[i]);
    scale = std::max(scale, std::fabs(value[i]));
    inside = inside || value[i] > 0;
  }
  for (int i = 0; i < m_; ++i)
    if (value[i] >= -1e-12 * scale) cuts_[n++] = {s_[i], false};
  const int vertices = n;
  for (int i = 0; i < m_; ++i) {
    const int j = (i + 1) % m_;
    const double ds = s_[j] - s_[i], dt = t_[j] - t_[i];
    const double a = r_.cuu * ds * ds + r_.cuv * ds * dt + r_.cvv * dt * dt;
    const double b =
        (r_.cu + 2 * r_.cuu * s_[i] + r_.cuv * t_[i]) * ds + (r_.cv + r_.cuv * s_[i] + 2 * r_.cvv * t_[i]) * dt;
    double root[2];
    const int k = roots_inside(a, b, r_.at(s_[i], t_[i]), 0, 1, root);
    for (int l = 0; l < k; ++l) cuts_[n++] = {s_[i] + root[l] * ds, false};
    // sign q rising above 0 between the edge's ends although both are at 0 or below: the conic through (or within
    // round-off of) both vertices, its roots on the edge lost to round-off just outside it, the region a sliver
    // along the edge (whose ends, within 1e-12 of 0, are cuts already)
    const double peak = -b / (2 * a);
    if (sign_ * a < 0 && peak > 0 && peak < 1) inside = inside || sign_ * (r_.at(s_[i], t_[i]) + 0.5 * b * peak) > 0;
  }
  if (r_.cvv != 0) {  // dq/dt = 0 on the line t = alpha + beta s; q there is a quadratic in s
    const double alpha = -r_.cv / (2 * r_.cvv), beta = -r_.cuv / (2 * r_.cvv);
    const double a = r_.cuu + r_.cuv * beta + r_.cvv * beta * beta;
    const double b = r_.cu + r_.cv * beta + r_.cuv * alpha + 2 * r_.cvv * alpha * beta;
    const double c = r_.c0 + r_.cv * alpha + r_.cvv * alpha * alpha;
    double root[2];
    const int k = roots_inside(a, b, c, smin_, smax_, root);
    for (int l = 0; l < k; ++l) cuts_[n++] = {root[l], true};
    if (a != 0) {
      const Complex disc = std::sqrt(Complex(b * b - 4 * a * c));
      singular_[n_singular_++] = (-b + disc) / (2 * a);
      singular_[n_singular_++] = (-b - disc) / (2 * a);
    } else if (b != 0) {
      singular_[n_singular_++] = -c / b;
    }
  } else if (r_.cuv != 0) {  // q linear in t: its slope vanishes on the line s = s*, where the root leaves
    const double star = -r_.cv / r_.cuv;
    if (star > smin_ && star < smax_) cuts_[n++] = {star, false};
  }
  // no vertex where sign q > 0, no crossing of an edge, no tangent inside (a closed curve has two): empty
  if (!inside && n == vertices) return false;
  std::sort(cuts_, cuts_ + n, [](const Breakpoint& x, const Breakpoint& y) { return x.s < y.s; });
  const double merge = 1e-13 * (smax_ - smin_);
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    if (kept > 0 && cuts_[i].s - cuts_[kept - 1].s <= merge) {
      cuts_[kept - 1].tangent = cuts_[kept - 1].tangent || cuts_[i].tangent;
      continue;
    }
    cuts_[kept++] = cuts_[i];
  }
  n = kept;
  return true;
}

void ConicRegion::run() {
  if (m_ < 3 || !(smax_ > smin_)) return;
  int n;
  if (!breakpoints(n)) return;
  // n points integrate a polynomial of degree k times a function analytic inside the ellipse rho to rho^-(2 n - k)
  const double order = std::max(2.0, 2.0 * static_cast<double>(outer_.nodes.size()) - degree_);
  rho_min_ = std::pow(10.0, 14.0 / order);
  const double merge = 1e-13 * (smax_ - smin_);
  for (int i = 0; i + 1 < n; ++i) {
    const double a = cuts_[i].s, b = cuts_[i + 1].s;
    if (!(b - a > merge)) continue;
    if (cuts_[i].tangent && cuts_[i + 1].tangent) {  // a tangent at each end: one for each half
      interval(a, 0.5 * (a + b), 0);
      interval(0.5 * (a + b), b, 0);
    } else {
      interval(a, b, 0);
    }
  }
}

// The outer rule on [from, to], in a variable in which the inner integral is smooth. Where the curve has a tangent
// along t at s = c (real), the inner length behaves like sqrt(s - c) there: with s = c + g sigma^2 (g = +-1, sigma
// from sqrt|from - c| to sqrt|to - c|) it is smooth in sigma, so each interval takes the real tangent nearest to it
// (at an end or beyond) as its centre c where it is close. Gauss-Legendre with n points converges like rho^-2n, rho
// the Bernstein ellipse of the interval (in sigma) through the nearest other tangent, real or complex, times the
// growth of an integrand of degree k there (rho^k): an interval with rho below 10^(14 / (2 n - k)) (an error near
// 1e-14) is halved, at most 40 times (two tangents 1e-6 apart need about 20).
void ConicRegion::interval(double from, double to, int depth) {
  const double tiny = 1e-12 * (smax_ - smin_);
  int centre = -1;
  double nearest = rho_min_;
  for (int k = 0; k < n_singular_; ++k) {
    if (singular_[k].imag() != 0) continue;
    const double c = singular_[k].real();
    if (c > std::min(from, to) + tiny && c < std::max(from, to) - tiny) continue;
    const double rho = ellipse((2.0 * singular_[k] - from - to) / (to - from));
    if (rho < nearest) {
      nearest = rho;
      centre = k;
    }
  }
  const double c = centre >= 0 ? singular_[centre].real() : 0;
  const double g = from + to > 2 * c ? 1.0 : -1.0;
  const double s0 = centre >= 0 ? std::sqrt(std::max(0.0, g * (from - c))) : from;
  const double s1 = centre >= 0 ? std::sqrt(std::max(0.0, g * (to - c))) : to;
  double rho = HUGE_VAL;
  for (int k = 0; k < n_singular_; ++k) {
    if (centre >= 0 && std::abs(singular_[k] - c) <= tiny) continue;
    if (centre < 0) {
      rho = std::min(rho, ellipse((2.0 * singular_[k] - s0 - s1) / (s1 - s0)));
    } else {
      const Complex sigma = std::sqrt(g * (singular_[k] - c));
      rho = std::min({rho, ellipse((2.0 * sigma - s0 - s1) / (s1 - s0)),
                      ellipse((-2.0 * sigma - s0 - s1) / (s1 - s0))});
    }
  }
  auto position = [&](double sigma) { return centre >= 0 ? c + g * sigma * sigma : sigma; };
  if (rho < rho_min_ && depth < 40) {
    const double mid = position(0.5 * (s0 + s1));
    interval(from, mid, depth + 1);
    interval(mid, to, depth + 1);
    return;
  }
  const double span = s1 - s0;
  const LineRule& rule = short_rule(std::fabs(span), centre >= 0 ? std::sqrt(smax_ - smin_) : smax_ - smin_, rho);
  for (size_t k = 0; k < rule.nodes.size(); ++k) {
    const double sigma = s0 + span * rule.nodes[k];
    line(position(sigma), rule.weights[k] * std::fabs(span) * (centre >= 0 ? 2 * std::fabs(sigma) : 1.0));
  }
}

// Fewer points on an interval short against the polygon: the outer rule is chosen for an integrand of degree D
// varying on the polygon's extent L (in the interval's variable), whose n-point rule on a span h is within
// 2^D (h / 4 L)^(2 n) of it (the Bernstein ellipse of size 4 L / h, where the polynomial is at most 2^D times its
// size on the interval); the tangents, as for the halving, need rho^-(2 n - k) <= 1e-14. The least n that meets
// both and 1e-15 (at least 2, at most the outer rule's; the outer rule where the halving stopped short of rho_min).
const LineRule& ConicRegion::short_rule(double h, double scale, double rho) const {
  const int full = static_cast<int>(outer_.nodes.size());
  const double ratio = 4 * scale / h;
  if (!(ratio > 100)) return outer_;
  if (!(rho > rho_min_)) return outer_;  // halved 40 times and still near a tangent: the full rule
  const double degree = 2.0 * full - 1;
  double n = (15 + 0.30103 * degree) / (2 * std::log10(ratio));
  if (rho < HUGE_VAL) n = std::max(n, 0.5 * (degree_ + 14 / std::log10(rho)));
  if (!(n < full)) return outer_;
  return line_rule(2 * std::max(2, static_cast<int>(std::ceil(n))) - 1);
}

void ConicRegion::line(double at, double ws) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int i = 0; i < m_; ++i) {
    const int j = (i + 1) % m_;
    if ((s_[i] - at) * (s_[j] - at) > 0 || s_[i] == s_[j]) continue;
    const double x = t_[i] + (at - s_[i]) / (s_[j] - s_[i]) * (t_[j] - t_[i]);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (!(hi > lo)) return;
  const double a = r_.cvv, b = r_.cv + r_.cuv * at, c = r_.c0 + at * (r_.cu + r_.cuu * at);
  double root[2];
  const int n = roots_inside(a, b, c, lo, hi, root);
  double ends[4] = {lo, root[0], root[1], hi};
  if (n < 2) ends[n + 1] = hi;
  for (int i = 0; i <= n; ++i) {
    const double t0 = ends[i], t1 = ends[i + 1], length = t1 - t0;
    const double mid = 0.5 * (t0 + t1);
    if (!(length > 0) || !(sign_ * (c + mid * (b + a * mid)) > 0)) continue;
    for (size_t l = 0; l < inner_.nodes.size(); ++l) {
      const double t = t0 + length * inner_.nodes[l];
      out_.push_back({cu_ + at * su_ + t * tu_, cv_ + at * sv_ + t * tv_, ws * inner_.weights[l] * length});
    }
  }
}

}  // namespace

void conic_region_rule(const double (*polygon)[2], int m, const Quadratic2& q, int sign, const LineRule& outer,
                       const LineRule& inner, int degree, std::vector<RegionPoint2>& out) {
  ConicRegion(polygon, m, q, sign, outer, inner, degree, out).run();
}

}  // namespace dlmfsi
