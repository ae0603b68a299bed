#include "integration/curved_method.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "errors.hpp"
#include "fe/matrix_inverse.hpp"
#include "fe/rules.hpp"
#include "geometry/polynomial_roots.hpp"
#include "sides/report.hpp"
#include "sides/sides.hpp"

namespace dlmfsi {

namespace {

// xi with X(xi) - origin = w, by Newton's method from xi; d1, d2: dX/dxi there. False where an iterate
// meets det dX/dxi <= 0 or strays far from the triangle, or 60 iterations do not settle (w beyond the
// image, where the polynomial map may fold).
bool invert(const MappedTriangle& mt, Point w, Point& xi, Point& d1, Point& d2) {
  for (int it = 0; it < 60; ++it) {
    Point x;
    mt.displacement(xi, x, d1, d2);
    const double det = cross(d1, d2);
    if (!(det > 0)) return false;
    const Point r = w - x;
    const Point step{cross(r, d2) / det, cross(d1, r) / det};
    xi = xi + step;
    if (!(std::fabs(xi.x) + std::fabs(xi.y) < 8)) return false;
    const double size = std::fabs(step.x) + std::fabs(step.y);
    // converged (after a step below 1e-9 the error is about nonlinearity * step^2, below round-off)
    if (size <= 1e-9) {
      mt.displacement(xi, x, d1, d2);
      return true;
    }
  }
  return false;
}

double least_barycentric(Point xi) { return std::min(std::min(xi.x, xi.y), 1 - xi.x - xi.y); }

// The Legendre polynomials L_0 .. L_n at u: (i + 1) L_i+1 = (2i + 1) u L_i - i L_i-1.
void legendre(double u, int n, double* l) {
  l[0] = 1;
  if (n >= 1) l[1] = u;
  for (int i = 1; i < n; ++i) l[i + 1] = ((2 * i + 1) * u * l[i] - i * l[i - 1]) / (i + 1);
}

}  // namespace

CurvedMethod::CurvedMethod(const FluidSide& fluid, const Integrand& integrand,
                           std::unique_ptr<TriangleIntegrator> straight, CouplingReport& counts)
    : fluid_(fluid), integrand_(integrand), points_(integrand, counts), straight_(std::move(straight)),
      counts_(counts) {
  if (integrand.chain || integrand.c1 == 0) batch_ = std::make_unique<BatchIntegrator>(integrand, counts);
}

bool CurvedMethod::applies(const Integrand& integrand, int map_degree) {
  return integrand.fluid.fitted() && integrand.multiplier.fitted() && integrand.fluid_degree >= 0 &&
         integrand.multiplier_degree >= 0 && map_degree >= 2 && map_degree <= kMaxPolynomialMapDegree;
}

double CurvedMethod::integrate(const MappedTriangle& mt, LocalBlock& block) {
  if (mt.affine || !mt.fitted()) return straight_->integrate(mt, block);
  const int d = mt.degree();
  const int degree = integrand_.multiplier_degree + integrand_.fluid_degree * d;
  if (degree > kMaxBoxDegree || (mt.straight && degree > kMaxStraightDegree)) return straight_->integrate(mt, block);
  if (degree != degree_) {
    degree_ = degree;
    gauss_legendre((degree + 3) / 2, edge_nodes_, edge_weights_);                     // degree + 1 along edges
    for (int extra = 0; extra <= kMaxArcExtraPoints; ++extra)
      gauss_legendre((degree + 3) / 2 + extra, arc_nodes_[extra], arc_weights_[extra]);
    padua_rule(degree);
  }
  edges_.set(mt);
  // the image's box widened by far more than its round-off: a fluid triangle or edge along an image edge is kept
  extent_ = std::max(edges_.hi.x - edges_.lo.x, edges_.hi.y - edges_.lo.y);
  const double margin = 1e-10 * extent_;
  box_lo_ = {edges_.lo.x - margin, edges_.lo.y - margin};
  box_hi_ = {edges_.hi.x + margin, edges_.hi.y + margin};
  for (int i = 0, s = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j, ++s) {
      sample_xi_[s] = {i / 4.0, j / 4.0};
      Point d1, d2;
      mt.displacement(sample_xi_[s], sample_x_[s], d1, d2);
    }
  if (stamp_of_.empty()) {  // the first curved triangle of the call: the marks over the fluid
    const size_t n = static_cast<size_t>(fluid_.mesh().size());
    stamp_of_.assign(n, 0u);
    done_of_.assign(n, 0u);
    slot_of_.assign(n, 0);
  }
  if (++stamp_ == 0) {
    std::fill(stamp_of_.begin(), stamp_of_.end(), 0u);
    std::fill(done_of_.begin(), done_of_.end(), 0u);
    stamp_ = 1;
  }
  done_.clear();
  edge_store_.clear();
  candidates_.clear();
  fluid_.grid().for_each_in_box(mt.origin() + edges_.lo, mt.origin() + edges_.hi, [&](int k) {
    if (stamp_of_[k] == stamp_) return;
    stamp_of_[k] = stamp_;
    candidates_.push_back(k);
  });
  double covered = 0;
  for (int k : candidates_) covered += piece(mt, k, block);
  // the image's area: int_T det dX/dxi, a polynomial of degree 2 (d - 1)
  double area = 0;
  for (const RulePoint& q : triangle_rule(2 * (d - 1))) {
    Point x, d1, d2;
    mt.displacement(q.xi, x, d1, d2);
    area += 0.5 * q.weight * cross(d1, d2);
  }
  const double outside = area - covered;
  return std::fabs(outside) <= 1e-12 * area ? 0 : outside;
}

void CurvedMethod::padua_rule(int degree) {
  // Padua points of degree D (first family): (cos(j pi / D), cos(k pi / (D + 1))), j + k even; the centre for D = 0.
  padua_u_.clear();
  padua_v_.clear();
  if (degree == 0) {
    padua_u_.push_back(0);
    padua_v_.push_back(0);
  }
  const double pi = std::acos(-1.0);
  for (int j = 0; degree > 0 && j <= degree; ++j)
    for (int k = 0; k <= degree + 1; ++k)
      if ((j + k) % 2 == 0) {
        padua_u_.push_back(std::cos(j * pi / degree));
        padua_v_.push_back(std::cos(k * pi / (degree + 1)));
      }
  // V_(ij),q = L_i(u_q) L_j(v_q), i + j <= D (row-major, a row per (ij)), and V^-1 (a row per point).
  const int n = static_cast<int>(padua_u_.size());
  std::vector<double> v(static_cast<size_t>(n) * n);
  double lu[kMaxBoxDegree + 2], lv[kMaxBoxDegree + 2];
  for (int q = 0; q < n; ++q) {
    legendre(padua_u_[q], degree, lu);
    legendre(padua_v_[q], degree, lv);
    for (int i = 0, a = 0; i <= degree; ++i)
      for (int j = 0; i + j <= degree; ++j, ++a) v[static_cast<size_t>(a) * n + q] = lu[i] * lv[j];
  }
  padua_inverse_ = inverse(v, n);
}

double CurvedMethod::piece(const MappedTriangle& mt, int kf, LocalBlock& block) {
  const Mesh& mesh = fluid_.mesh();
  FluidTriangle& f = fluid_triangle_;
  for (int j = 0; j < 3; ++j) f.w[j] = mesh.vertex(kf, j) - mt.origin();
  for (int j = 0; j < 3; ++j) f.e[j] = f.w[(j + 1) % 3] - f.w[j];
  // K's box against the image's
  const Point lo = box_lo_, hi = box_hi_;
  const Point* w = f.w;
  if (std::max({w[0].x, w[1].x, w[2].x}) < lo.x || std::min({w[0].x, w[1].x, w[2].x}) > hi.x ||
      std::max({w[0].y, w[1].y, w[2].y}) < lo.y || std::min({w[0].y, w[1].y, w[2].y}) > hi.y)
    return 0;
  find_crossings();
  boundary_.clear();
  add_solid_edges();
  add_fluid_edges(mt, kf);
  if (boundary_.empty()) return 0;
  return integrate_piece(mt, kf, block);
}

void CurvedMethod::find_crossings() {
  FluidTriangle& f = fluid_triangle_;
  const int d = edges_.degree;
  for (int j = 0; j < 3; ++j) {
    const double scale = 1e-13 * (std::fabs(f.e[j].x) + std::fabs(f.e[j].y)) * extent_;
    for (int i = 0; i < 3; ++i) {
      double sum = 0;
      for (int k = 0; k <= d; ++k) {
        f.q[i][j][k] = cross(f.e[j], k == 0 ? edges_.coefficient[i][0] - f.w[j] : edges_.coefficient[i][k]);
        sum += std::fabs(f.q[i][j][k]);
      }
      f.coincident[i][j] = sum <= scale;
      f.at_corner[j][i] = f.q[i][j][0];
    }
  }
  for (int i = 0; i < 3; ++i) f.breaks[i] = 0;
  for (int j = 0; j < 3; ++j) crossings_[j].clear();
  // K's box: an image edge whose control points' box misses it has no part in K and no crossing with K's edges
  // (the boxes widened by far more than their round-off, so that an image edge along a fluid edge is kept)
  const double margin = 1e-10 * extent_;
  const Point klo{std::min({f.w[0].x, f.w[1].x, f.w[2].x}) - margin, std::min({f.w[0].y, f.w[1].y, f.w[2].y}) - margin};
  const Point khi{std::max({f.w[0].x, f.w[1].x, f.w[2].x}) + margin, std::max({f.w[0].y, f.w[1].y, f.w[2].y}) + margin};
  for (int i = 0; i < 3; ++i)
    f.edge_meets[i] = !(edges_.edge_hi[i].x < klo.x || edges_.edge_lo[i].x > khi.x || edges_.edge_hi[i].y < klo.y ||
                        edges_.edge_lo[i].y > khi.y);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3 && f.edge_meets[i]; ++j) {
      if (f.coincident[i][j]) continue;
      // all control points strictly on one side: no crossing
      int above = 0, below = 0;
      for (int k = 0; k <= d; ++k) {
        const double h = cross(f.e[j], edges_.control[i][k] - f.w[j]);
        above += h > 0;
        below += h < 0;
      }
      if (above == d + 1 || below == d + 1) continue;
      double roots[kMaxRootsDegree];
      const int n = roots_in(f.q[i][j], d, 0, 1, f.at_corner[j][i], f.at_corner[j][(i + 1) % 3], roots);
      for (int r = 0; r < n; ++r) {
        f.t[i][f.breaks[i]++] = roots[r];
        const Point x = edges_.at(i, roots[r]) - f.w[j];
        const Point e = f.e[j];
        const double tau = (x.x * e.x + x.y * e.y) / (e.x * e.x + e.y * e.y);
        if (tau >= -1e-13 && tau <= 1 + 1e-13)
          crossings_[j].push_back({std::min(1.0, std::max(0.0, tau)),
                                   ImageEdges::start(i) + roots[r] * ImageEdges::direction(i)});
      }
    }
}

void CurvedMethod::add_solid_edges() {
  FluidTriangle& f = fluid_triangle_;
  const int d = edges_.degree;
  // T's edges 1 and 2 (edge 0, xi2 = 0, has no share of ∮ G dxi2).
  for (int i = 1; i < 3; ++i) {
    if (!f.edge_meets[i]) continue;
    double* b = f.t[i];
    int n = f.breaks[i];
    b[n++] = 0;
    b[n++] = 1;
    std::sort(b, b + n);
    const Point start = ImageEdges::start(i), direction = ImageEdges::direction(i);
    for (int s = 0; s + 1 < n; ++s) {
      const double ta = b[s], tb = b[s + 1];
      if (!(tb > ta)) continue;
      const double tm = 0.5 * (ta + tb);
      bool in = true;
      for (int j = 0; j < 3 && in; ++j) {
        if (f.coincident[i][j]) {  // along K's edge j: counted where T and K lie on the same side
          const Point tangent = edges_.tangent(i, tm);
          in = tangent.x * f.e[j].x + tangent.y * f.e[j].y > 0;
        } else {
          in = polynomial_value(f.q[i][j], d, tm) >= 0;
        }
      }
      if (!in) continue;
      for (size_t g = 0; g < edge_nodes_.size(); ++g)
        boundary_.push_back({start + (ta + (tb - ta) * edge_nodes_[g]) * direction,
                             edge_weights_[g] * (tb - ta) * direction.y});
    }
  }
}

void CurvedMethod::add_fluid_edges(const MappedTriangle& mt, int kf) {
  const Mesh& mesh = fluid_.mesh();
  StoredEdges mine;
  for (int j = 0; j < 3; ++j) {
    mine.begin[j] = mine.end[j] = 0;
    // K's edge j is edge jn of its neighbour kn: when kn's piece has been done, the same points, reversed
    const int kn = mesh.neighbours[kf][(j + 2) % 3];
    int jn = -1;
    if (kn >= 0 && done_of_[kn] == stamp_)
      for (int i = 0; i < 3; ++i)
        if (mesh.neighbours[kn][(i + 2) % 3] == kf) jn = i;
    if (jn >= 0) {
      const StoredEdges& theirs = done_[static_cast<size_t>(slot_of_[kn])];
      for (int p = theirs.begin[jn]; p < theirs.end[jn]; ++p)
        boundary_.push_back({edge_store_[static_cast<size_t>(p)].xi, -edge_store_[static_cast<size_t>(p)].weight});
      continue;
    }
    const size_t from = boundary_.size();
    add_fluid_edge(mt, j);
    mine.begin[j] = static_cast<int>(edge_store_.size());
    edge_store_.insert(edge_store_.end(), boundary_.begin() + static_cast<std::ptrdiff_t>(from), boundary_.end());
    mine.end[j] = static_cast<int>(edge_store_.size());
  }
  done_of_[kf] = stamp_;
  slot_of_[kf] = static_cast<int>(done_.size());
  done_.push_back(mine);
}

void CurvedMethod::add_fluid_edge(const MappedTriangle& mt, int j) {
  const FluidTriangle& f = fluid_triangle_;
  const Point lo = box_lo_, hi = box_hi_;
  bool along_image = false;
  for (int i = 0; i < 3; ++i) along_image = along_image || f.coincident[i][j];
  // on an image edge (coincident boundaries) a point is not inside: T's edge carries that part
  const double margin = along_image ? 1e-9 : 0;
  std::vector<Crossing>& c = crossings_[j];
  const Point unknown{NAN, NAN};
  c.push_back({0, unknown});
  c.push_back({1, unknown});
  std::sort(c.begin(), c.end(), [](const Crossing& a, const Crossing& b) { return a.tau < b.tau; });
  for (size_t s = 0; s + 1 < c.size(); ++s) {
    const Crossing a = c[s], b = c[s + 1];
    if (!(b.tau > a.tau)) continue;
    const Point wm = f.w[j] + 0.5 * (a.tau + b.tau) * f.e[j];
    if (wm.x < lo.x || wm.x > hi.x || wm.y < lo.y || wm.y > hi.y) continue;
    const bool known_a = !std::isnan(a.xi.x), known_b = !std::isnan(b.xi.x);
    Point guess = known_a && known_b ? 0.5 * (a.xi + b.xi) : known_a ? a.xi : known_b ? b.xi : Point{-1, -1};
    Point xm;
    if (!inside_image(mt, wm, guess, margin, xm)) continue;
    auto end = [&](const Crossing& cr) {
      if (!std::isnan(cr.xi.x)) return cr.xi;
      Point xi = xm, d1, d2;
      if (!invert(mt, f.w[j] + cr.tau * f.e[j], xi, d1, d2))
        throw Error("could not pull a fluid vertex back into " + mt.name() + " (Newton's method)");
      return xi;
    };
    arc(mt, f.w[j], f.e[j], a.tau, b.tau, end(a), end(b));
  }
}

double CurvedMethod::integrate_piece(const MappedTriangle& mt, int kf, LocalBlock& block) {
  // The piece lies in the box of its boundary, [x0, x1] x [y0, y1]; u, v in [-1, 1] across it.
  Point low{HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL};
  for (const BoundaryPoint& p : boundary_) {
    low = {std::min(low.x, p.xi.x), std::min(low.y, p.xi.y)};
    high = {std::max(high.x, p.xi.x), std::max(high.y, p.xi.y)};
  }
  const double hx = 0.5 * (high.x - low.x), hy = 0.5 * (high.y - low.y);
  if (!(hx > 0 && hy > 0)) return 0;  // a segment: no area
  // The piece's moments of the Legendre products L_i(u) L_j(v), i + j <= D, by Green's theorem:
  //   M_ij = ∮ hx Λ_i(u) L_j(v) dxi2,   Λ_i(u) = int_-1^u L_i = (L_i+1(u) - L_i-1(u)) / (2i + 1), Λ_0 = u + 1.
  const int D = degree_, count = static_cast<int>(padua_u_.size());
  moments_.assign(static_cast<size_t>(D + 1) * (D + 1), 0);
  double lu[kMaxBoxDegree + 2], lv[kMaxBoxDegree + 2];
  for (const BoundaryPoint& p : boundary_) {
    if (p.weight == 0) continue;
    const double u = (p.xi.x - low.x) / hx - 1, v = (p.xi.y - low.y) / hy - 1;
    legendre(u, D + 1, lu);
    legendre(v, D, lv);
    for (int i = 0; i <= D; ++i) {
      const double antiderivative = hx * p.weight * (i == 0 ? u + 1 : (lu[i + 1] - lu[i - 1]) / (2 * i + 1));
      for (int j = 0; i + j <= D; ++j) moments_[static_cast<size_t>(i) * (D + 1) + j] += antiderivative * lv[j];
    }
  }
  block.enter_fluid_element(fluid_.dofs(kf));
  ++counts_.pieces;
  const double solid_jacobian = area2(mt.solid[0], mt.solid[1], mt.solid[2]);  // ds = this dxi
  double area = 0;
  rule_y_.resize(count);
  rule_xi_.resize(count);
  rule_weight_.resize(count);
  rule_jacobian_.resize(count);
  for (int point = 0; point < count; ++point) {
    // w = sum_ij (V^-1)_point,ij M_ij
    const double* row = &padua_inverse_[static_cast<size_t>(point) * count];
    double weight = 0;
    for (int i = 0, a = 0; i <= D; ++i)
      for (int j = 0; i + j <= D; ++j, ++a) weight += row[a] * moments_[static_cast<size_t>(i) * (D + 1) + j];
    const Point xi{low.x + hx * (padua_u_[point] + 1), low.y + hy * (padua_v_[point] + 1)};
    Point x, d1, d2;
    mt.displacement(xi, x, d1, d2);  // x = X(xi) - origin: the fluid basis is evaluated at the local point
    MapValue value;
    mt.set_jacobian(d1, d2, value);
    area += weight * cross(d1, d2);
    rule_y_[point] = x;
    rule_xi_[point] = xi;
    rule_weight_[point] = weight * solid_jacobian;
    rule_jacobian_[point] = {value.jac[0][0], value.jac[0][1], value.jac[1][0], value.jac[1][1]};
  }
  if (batch_) {
    batch_->integrate_points(mt, kf, count, rule_y_.data(), mt.origin(), rule_xi_.data(), rule_weight_.data(),
                             rule_jacobian_.data(), block);
  } else {
    for (int point = 0; point < count; ++point) {
      const std::array<double, 4>& j = rule_jacobian_[point];
      const double jac[2][2] = {{j[0], j[1]}, {j[2], j[3]}};
      points_.add_point(kf, rule_y_[point], mt.origin(), mt.k, rule_xi_[point], rule_weight_[point], jac, block);
    }
  }
  return area;
}

void CurvedMethod::arc(const MappedTriangle& mt, Point w0, Point e, double ta, double tb, Point xa, Point xb) {
  struct Segment {
    double ta, tb;
    Point xa, xb;
    int depth;
    std::vector<BoundaryPoint> points;  // its Gauss rule's
  };
  auto fail = [&]() { return Error("could not pull a fluid edge back into " + mt.name() + " (Newton's method)"); };
  // Nearly straight arcs: with X's jacobian varying by r = 4 nonlinearity L relative along an arc of length L
  // (in xi), the rule with `extra` points more than the polynomial part needs leaves about r^(2 extra + 1).
  const double r = 4 * mt.nonlinearity * (std::fabs(xb.x - xa.x) + std::fabs(xb.y - xa.y));
  for (int extra = 1; extra <= kMaxArcExtraPoints; ++extra)
    if (std::pow(r, 2 * extra + 1) <= 1e-17) {
      if (!arc_rule(mt, w0, e, ta, tb, xa, xb, extra, boundary_points_)) throw fail();
      boundary_.insert(boundary_.end(), boundary_points_.begin(), boundary_points_.end());
      return;
    }
  // Otherwise halves against the whole until they agree.
  std::vector<Segment> stack(1);
  stack[0] = {ta, tb, xa, xb, 0, {}};
  if (!arc_rule(mt, w0, e, ta, tb, xa, xb, kArcExtraPoints, stack[0].points)) throw fail();
  while (!stack.empty()) {
    Segment s = std::move(stack.back());
    stack.pop_back();
    const double tm = 0.5 * (s.ta + s.tb);
    Point xm = 0.5 * (s.xa + s.xb), d1, d2;
    if (!invert(mt, w0 + tm * e, xm, d1, d2)) throw fail();
    Segment left{s.ta, tm, s.xa, xm, s.depth + 1, {}}, right{tm, s.tb, xm, s.xb, s.depth + 1, {}};
    if (!arc_rule(mt, w0, e, s.ta, tm, s.xa, xm, kArcExtraPoints, left.points) ||
        !arc_rule(mt, w0, e, tm, s.tb, xm, s.xb, kArcExtraPoints, right.points))
      throw fail();
    // the whole's and the halves' moments relative to s.xa, of degree 1, degree + 1 and degree + 1 in both
    // coordinates (k = 1, degree + 1, degree + 1), against the size of such a moment on this arc, L^(k+1),
    // and the round-off of the points' reference coordinates (about eps), eps L^k
    double whole[3] = {0, 0, 0}, halves[3] = {0, 0, 0};
    add_moments(s.points, s.xa, whole);
    add_moments(left.points, s.xa, halves);
    add_moments(right.points, s.xa, halves);
    const double length = std::max(std::fabs(s.xb.x - s.xa.x) + std::fabs(s.xb.y - s.xa.y), 1e-300);
    const double high = std::pow(length, degree_ + 1);
    const double tolerance[3] = {(kArcTolerance * length + kArcRoundOff) * length,
                                 (kArcTolerance * length + kArcRoundOff) * high,
                                 (kArcTolerance * length + kArcRoundOff) * high};
    bool agree = true;
    for (int k = 0; k < 3; ++k) agree = agree && std::fabs(whole[k] - halves[k]) <= tolerance[k];
    if (agree || s.depth + 1 >= kMaxArcDepth) {
      boundary_.insert(boundary_.end(), left.points.begin(), left.points.end());
      boundary_.insert(boundary_.end(), right.points.begin(), right.points.end());
      continue;
    }
    stack.push_back(std::move(left));
    stack.push_back(std::move(right));
  }
}

bool CurvedMethod::arc_rule(const MappedTriangle& mt, Point w0, Point e, double ta, double tb, Point xa, Point xb,
                            int extra, std::vector<BoundaryPoint>& points) const {
  points.clear();
  const std::vector<double>&nodes = arc_nodes_[extra], &weights = arc_weights_[extra];
  for (size_t g = 0; g < nodes.size(); ++g) {
    const double u = nodes[g];
    Point xi = xa + u * (xb - xa), d1, d2;
    if (!invert(mt, w0 + (ta + (tb - ta) * u) * e, xi, d1, d2)) return false;
    // dxi/dtau = (dX/dxi)^-1 e: its second component
    points.push_back({xi, weights[g] * (tb - ta) * cross(d1, e) / cross(d1, d2)});
  }
  return true;
}

void CurvedMethod::add_moments(const std::vector<BoundaryPoint>& points, Point ref, double moments[3]) const {
  for (const BoundaryPoint& p : points) {
    const double a = p.xi.x - ref.x, b = p.xi.y - ref.y;
    moments[0] += p.weight * a;
    double an = a, bn = 1;  // a^(degree + 1), b^degree
    for (int k = 0; k < degree_; ++k) an *= a, bn *= b;
    moments[1] += p.weight * an;
    moments[2] += p.weight * a * bn;
  }
}

bool CurvedMethod::inside_image(const MappedTriangle& mt, Point w, Point guess, double margin, Point& xi) const {
  Point d1, d2;
  if (least_barycentric(guess) >= -0.25) {
    xi = guess;
    // inside when found inside; found outside (or not found), the nearest sample decides: beyond T the
    // polynomial map may take w again
    if (invert(mt, w, xi, d1, d2) && least_barycentric(xi) >= margin) return true;
  }
  int nearest = 0;
  double best = HUGE_VAL;
  for (int s = 0; s < 15; ++s) {
    const Point r = sample_x_[s] - w;
    const double distance = r.x * r.x + r.y * r.y;
    if (distance < best) best = distance, nearest = s;
  }
  xi = sample_xi_[nearest];
  return invert(mt, w, xi, d1, d2) && least_barycentric(xi) >= margin;
}

}  // namespace dlmfsi
