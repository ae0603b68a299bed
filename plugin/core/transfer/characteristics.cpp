#include "transfer/characteristics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.hpp"
#include "fe/lattice.hpp"
#include "fe/rules.hpp"
#include "sides/validation.hpp"

namespace dlmfsi {

namespace {

// Barycentric coordinates within this of an edge count as on it: the rounding of a point moving along an edge
// (a velocity parallel to it) must not make the walk cross back and forth. A foot moves by at most this
// fraction of its triangle's size.
constexpr double kOnEdge = 1e-10;
// Crossings in a row that do not move the walk (through a vertex, from triangle to triangle around it)
// before it stops there; and crossings in all before the walk is refused (a velocity far too large for dt).
constexpr int kMaxIdle = 64;
constexpr int kMaxCrossings = 100000;

bool listed(const std::vector<int>& list, int c) { return std::find(list.begin(), list.end(), c) != list.end(); }

}  // namespace

namespace {

// Do the two sides hold the same triangles in the same order (the same mesh, renumbered alike)?
bool same_triangles(const FluidSide& a, const FluidSide& b) {
  if (&a == &b) return true;
  const Mesh &ma = a.mesh(), &mb = b.mesh();
  if (ma.size() != mb.size() || a.scale() != b.scale()) return false;
  for (int k = 0; k < ma.size(); ++k)
    for (int i = 0; i < 3; ++i)
      if (ma.vertex(k, i) != mb.vertex(k, i)) return false;
  return true;
}

}  // namespace

Characteristics::Characteristics(const FluidSide& side, const CharacteristicsTerm& term,
                                 const FluidSide* velocity_side)
    : side_(side), velocity_side_(velocity_side ? *velocity_side : side), term_(term) {
  const PolynomialBasis& basis = side.basis();
  if (!basis.fitted())
    throw Error("convect: the space is not a polynomial element on each triangle (its field cannot be evaluated at "
                "the feet)");
  if (!velocity_side_.basis().fitted())
    throw Error("convect: the velocity's space is not a polynomial element on each triangle (its velocity cannot "
                "be traced)");
  if (!same_triangles(side, velocity_side_))
    throw Error("convect: the velocity's space and the field's are not on the same mesh");
  if (!term.velocity || !term.field) throw Error("convect: the velocity or the field has no values");
  if (!std::isfinite(term.dt)) throw Error("convect: dt=" + option_value(term.dt) + " is not finite");
  if (!std::isfinite(term.c)) throw Error("convect: c=" + option_value(term.c) + " is not finite");
  if (term.degree < 0 || term.degree > 60)
    throw Error("convect: qforder=" + std::to_string(term.degree) + " out of range (0 to 60)");
  if (term.components.empty()) throw Error("convect: no field component listed");
  if (term.u_component == term.v_component)
    throw Error("convect: the velocity's two components are the same (" + std::to_string(term.u_component) + ")");
  for (int c : term.components)
    if (std::count(term.components.begin(), term.components.end(), c) > 1)
      throw Error("convect: field component " + std::to_string(c) + " listed twice");
  for (int c : term.components)
    if (!listed(side.components(), c)) throw Error("convect: field component " + std::to_string(c) + " not prepared");
  for (int c : {term.u_component, term.v_component})
    if (!listed(velocity_side_.components(), c))
      throw Error("convect: velocity component " + std::to_string(c) + " not prepared");

  terms_ = monomial_count(basis.degree());
  velocity_terms_ = monomial_count(velocity_side_.basis().degree());
  step_ = std::ldexp(term.dt, -side.scale());
  const std::vector<int> uv{term.u_component, term.v_component};
  velocity_ = local_polynomials(velocity_side_, term.velocity, uv);
  // The field that is the velocity itself (the momentum's characteristics: convect([u,v],dt,u), ...(v)) has
  // the same polynomials: formed once.
  if (&velocity_side_ != &side || term.field != term.velocity || term.components != uv)
    own_field_ = local_polynomials(side, term.field, term.components);
  field_ = own_field_.empty() ? &velocity_ : &own_field_;
  const int nc = side.space().components();
  const std::vector<int>& functions = basis.functions();
  for (size_t f = 0; f < functions.size(); ++f) {
    const auto slot = std::find(term.components.begin(), term.components.end(), functions[f] % nc);
    if (slot == term.components.end()) continue;
    tested_.push_back(static_cast<int>(f));
    tested_slot_.push_back(static_cast<int>(slot - term.components.begin()));
  }
}

std::vector<double> Characteristics::local_polynomials(const FluidSide& side, const double* values,
                                                       const std::vector<int>& comps) {
  const PolynomialBasis& basis = side.basis();
  const int nc = side.space().components();
  const int terms = monomial_count(basis.degree());
  const std::vector<int>& functions = basis.functions();
  const size_t width = comps.size() * terms;
  std::vector<double> polys(side.mesh().size() * width, 0.0);
  std::vector<int> slot(functions.size(), -1);  // per fitted function: its component's place in comps
  for (size_t f = 0; f < functions.size(); ++f) {
    const auto c = std::find(comps.begin(), comps.end(), functions[f] % nc);
    if (c != comps.end()) slot[f] = static_cast<int>(c - comps.begin());
  }
  for (int k = 0; k < side.mesh().size(); ++k) {
    const double* coef = basis.coefficients(k);
    const int* dofs = side.dofs(k);
    double* out = &polys[k * width];
    for (size_t f = 0; f < functions.size(); ++f) {
      if (slot[f] < 0) continue;
      const double v = values[dofs[functions[f] / nc]];
      double* o = out + slot[f] * terms;
      for (int m = 0; m < terms; ++m) o[m] += v * coef[f * terms + m];
    }
  }
  return polys;
}

namespace {

// The monomials of degree <= d at xi and a polynomial's value from them; NM > 0 fixes their number (and the
// degree) at compile time.
template <int NM>
void monomials_at(int degree, Point xi, double* m) {
  constexpr int kDegree = NM == 1 ? 0 : NM == 3 ? 1 : NM == 6 ? 2 : 3;
  monomial_values(NM > 0 ? kDegree : degree, xi, m);
}

template <int NM>
double polynomial(const double* coef, const double* monomials, int terms) {
  double s = 0;
  const int n = NM > 0 ? NM : terms;
  for (int m = 0; m < n; ++m) s += coef[m] * monomials[m];
  return s;
}

}  // namespace

template <int NV>
Point Characteristics::velocity(int k, Point xi) const {
  double m[monomial_count(kMaxLatticeDegree)];
  monomials_at<NV>(velocity_side_.basis().degree(), xi, m);
  const double* uv = &velocity_[static_cast<size_t>(k) * 2 * velocity_terms_];
  return {polynomial<NV>(uv, m, velocity_terms_), polynomial<NV>(uv + velocity_terms_, m, velocity_terms_)};
}

// The walk in reference coordinates: on triangle k the velocity w at xi, and the point it leads to,
// xi + (d xi / d x) (left dt w) with the part `left` of dt still to follow.
template <int NV>
Foot Characteristics::walk(int k, Point xi, CharacteristicsReport* report) const {
  const Mesh& mesh = side_.mesh();
  const int start = k;
  double left = 1;
  int idle = 0;
  for (int crossings = 0;; ++crossings) {
    if (crossings > kMaxCrossings)
      throw Error("convect: the walk from fluid triangle " + std::to_string(side_.space().original()[start]) +
                  " crossed more than " + std::to_string(kMaxCrossings) + " edges (a velocity far too large for dt?)");
    const Point w = velocity<NV>(k, xi);
    if (!std::isfinite(w.x) || !std::isfinite(w.y))
      throw Error("convect: the velocity is not finite in fluid triangle " +
                  std::to_string(side_.space().original()[k]));
    const double* j = side_.basis().inverse_jacobian(k);
    const Point d{left * step_ * w.x, left * step_ * w.y};
    const Point there{xi.x + j[0] * d.x + j[1] * d.y, xi.y + j[2] * d.x + j[3] * d.y};
    const double from[3] = {1 - xi.x - xi.y, xi.x, xi.y};
    const double to[3] = {1 - there.x - there.y, there.x, there.y};
    // The first edge the segment from -> to leaves by: edge i (opposite vertex i) at the fraction
    // s = from_i / (from_i - to_i) of the segment, over the i with to_i < 0.
    int edge = -1;
    double s = 1;
    for (int i = 0; i < 3; ++i)
      if (to[i] < -kOnEdge) {
        const double si = from[i] > 0 ? from[i] / (from[i] - to[i]) : 0;
        if (edge < 0 || si < s) edge = i, s = si;
      }
    if (edge < 0) {  // the time is spent in this triangle
      Point end{std::max(0.0, there.x), std::max(0.0, there.y)};
      const double sum = end.x + end.y;
      if (sum > 1) end = {end.x / sum, end.y / sum};
      return {k, end, false};
    }
    double at[3];
    for (int i = 0; i < 3; ++i) at[i] = std::max(0.0, from[i] + s * (to[i] - from[i]));
    at[edge] = 0;
    left *= 1 - s;
    idle = s > 0 ? 0 : idle + 1;
    const int next = mesh.neighbours[k][edge];
    if (next < 0 || idle > kMaxIdle) {
      if (report && next < 0) ++report->boundary_stops;
      return {k, {at[1], at[2]}, next < 0};
    }
    if (report) ++report->crossings;
    // The crossing in next's coordinates: the edge's two vertices keep their weights, the third gets 0.
    const int a = mesh.triangles[k][(edge + 1) % 3], b = mesh.triangles[k][(edge + 2) % 3];
    double in_next[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.triangles[next][i];
      if (v == a) in_next[i] = at[(edge + 1) % 3];
      if (v == b) in_next[i] = at[(edge + 2) % 3];
    }
    k = next;
    xi = {in_next[1], in_next[2]};
  }
}

template <int NV, int NF>
void Characteristics::integrate(double* b, CharacteristicsReport* report) const {
  const PolynomialBasis& basis = side_.basis();
  const std::vector<RulePoint>& rule = triangle_rule(term_.degree);
  const int n = static_cast<int>(rule.size());
  const int nc = side_.space().components();
  const int slots = static_cast<int>(term_.components.size());
  const std::vector<int>& functions = basis.functions();
  std::fill(b, b + side_.space().dof_count(), 0.0);
  std::vector<Point> points(n);
  for (int q = 0; q < n; ++q) points[q] = rule[q].xi;
  // The test functions at the rule's points: the same on every triangle that shares the basis's fit.
  std::vector<double> phi(functions.size() * n), shared_phi(functions.size() * n), g(static_cast<size_t>(n) * slots);
  int shared_k = -1;
  for (int k = 0; k < side_.mesh().size() && shared_k < 0; ++k)
    if (basis.shared(k)) shared_k = k;
  if (shared_k >= 0) basis.evaluate_points(shared_k, points.data(), n, shared_phi.data(), nullptr, nullptr);
  double m[monomial_count(kMaxLatticeDegree)];
  // The side's coordinates are the caller's times 2^-scale: areas come back with 2^(2 scale).
  const double factor = std::ldexp(term_.c, 2 * side_.scale());
  const Mesh& mesh = side_.mesh();
  for (int k = 0; k < mesh.size(); ++k) {
    Point p[3];
    mesh.corners(k, p);
    const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
    const bool shared = basis.shared(k);
    if (!shared) basis.evaluate_points(k, points.data(), n, phi.data(), nullptr, nullptr);
    const double* tests = shared ? shared_phi.data() : phi.data();
    for (int q = 0; q < n; ++q) {
      const Foot foot = walk<NV>(k, points[q], report);
      monomials_at<NF>(basis.degree(), foot.xi, m);
      const double* f = &(*field_)[static_cast<size_t>(foot.k) * slots * terms_];
      for (int s = 0; s < slots; ++s) g[q * slots + s] = rule[q].weight * polynomial<NF>(f + s * terms_, m, terms_);
    }
    if (report) report->points += n;
    const int* dofs = side_.dofs(k);
    for (size_t t = 0; t < tested_.size(); ++t) {
      const int f = tested_[t], s = tested_slot_[t];
      double sum = 0;
      for (int q = 0; q < n; ++q) sum += g[q * slots + s] * tests[f * n + q];
      b[dofs[functions[f] / nc]] += factor * area * sum;
    }
  }
}

Foot Characteristics::trace(int k, Point xi, CharacteristicsReport* report) const {
  switch (velocity_terms_) {
    case 1: return walk<1>(k, xi, report);
    case 3: return walk<3>(k, xi, report);
    case 6: return walk<6>(k, xi, report);
    case 10: return walk<10>(k, xi, report);
    default: return walk<0>(k, xi, report);
  }
}

// The field's number of monomials fixed at compile time when it is the velocity's (one space), else not.
template <int NV>
void Characteristics::integrate_field(double* b, CharacteristicsReport* report) const {
  if (terms_ == velocity_terms_)
    integrate<NV, NV>(b, report);
  else
    integrate<NV, 0>(b, report);
}

void Characteristics::assemble(double* b, CharacteristicsReport* report) const {
  switch (velocity_terms_) {
    case 1: integrate_field<1>(b, report); break;
    case 3: integrate_field<3>(b, report); break;
    case 6: integrate_field<6>(b, report); break;
    case 10: integrate_field<10>(b, report); break;
    default: integrate<0, 0>(b, report); break;
  }
}

}  // namespace dlmfsi
