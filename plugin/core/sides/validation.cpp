#include "sides/validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "errors.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

template <int D>
void check_components(const BasisOf<D>& basis, const std::vector<int>& components, const std::string& side,
                      const std::string& space) {
  for (int c : components)
    if (c < 0 || c >= basis.components())
      throw Error(side + " component " + std::to_string(c) + " out of range (the " + space + " has " +
                  std::to_string(basis.components()) + ")");
}

std::string option_value(double v) {
  if (std::isnan(v)) return "NaN";
  char s[40];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

template <int D>
void check_pairs_and_weights(const BasisOf<D>& fluid_space, const BasisOf<D>& multiplier, const CouplingOptions& opt) {
  const auto& f = opt.fluid_components;
  const auto& s = opt.solid_components;
  if (f.size() != s.size())
    throw Error("fluid and solid component lists differ in length (" + std::to_string(f.size()) + " and " +
                std::to_string(s.size()) + ")");
  if (f.empty()) throw Error("no components to couple (fluid and solid are empty)");
  check_components(fluid_space, f, "fluid", "fluid space");
  check_components(multiplier, s, "solid", "multiplier space");
  for (size_t q = 0; q < f.size(); ++q)
    for (size_t p = 0; p < q; ++p)
      if (f[p] == f[q] && s[p] == s[q])
        throw Error("the pair fluid component " + std::to_string(f[q]) + " with solid component " +
                    std::to_string(s[q]) + " is listed twice (positions " + std::to_string(p) + " and " +
                    std::to_string(q) + " of fluid= and solid=)");
  if (!std::isfinite(opt.c1)) throw Error("c1=" + option_value(opt.c1) + " is not finite");
  if (!std::isfinite(opt.c2)) throw Error("c2=" + option_value(opt.c2) + " is not finite");
}

template void check_components<2>(const BasisOf<2>&, const std::vector<int>&, const std::string&, const std::string&);
template void check_components<3>(const BasisOf<3>&, const std::vector<int>&, const std::string&, const std::string&);
template void check_pairs_and_weights<2>(const BasisOf<2>&, const BasisOf<2>&, const CouplingOptions&);
template void check_pairs_and_weights<3>(const BasisOf<3>&, const BasisOf<3>&, const CouplingOptions&);

void check_qforder(long qforder) {
  if (qforder < -1 || qforder > kMaxQforder)
    throw Error("qforder=" + std::to_string(qforder) + " out of range (0 to " + std::to_string(kMaxQforder) +
                ", or -1 for the automatic choice: a rule of degree " + std::to_string(kMaxQforder) +
                " has 961 points per piece)");
}

void check_subdivide(long subdivide) {
  if (subdivide < -1 || subdivide > kMaxSubdivide)
    throw Error("subdivide=" + std::to_string(subdivide) + " out of range (0 to " + std::to_string(kMaxSubdivide) +
                ", or -1 for the default: each curved solid triangle is split into 4^subdivide parts, at most " +
                std::to_string(1 << (2 * kMaxSubdivide)) + ")");
}

void check_options(const Basis& fluid_space, const Basis& multiplier, const CouplingOptions& opt) {
  check_pairs_and_weights(fluid_space, multiplier, opt);
  if (opt.gradient == CouplingOptions::Gradient::Listing && opt.fluid_components.size() != 2)
    throw Error("gradient=\"listing\" needs exactly two component pairs (a 2D vector field)");
  check_qforder(opt.qforder);
  check_subdivide(opt.subdivide);
  if (!(opt.tol > 0 && opt.tol < 1)) throw Error("tol=" + option_value(opt.tol) + " must lie in (0, 1)");
  if (!(opt.outside_tol >= 0)) throw Error("outsidetol=" + option_value(opt.outside_tol) + " must be a number >= 0");
  if (opt.threads < 1) throw Error("threads=" + std::to_string(opt.threads) + " must be at least 1");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts)
    throw Error("part=[" + std::to_string(opt.part) + ", " + std::to_string(opt.parts) +
                "] needs 0 <= rank < size");
}

namespace {

// Is v strictly between p and q? (v on the line pq: exact comparisons along the longer coordinate.)
bool strictly_between(Point v, Point p, Point q) {
  if (std::fabs(q.x - p.x) >= std::fabs(q.y - p.y))
    return (v.x > p.x && v.x < q.x) || (v.x < p.x && v.x > q.x);
  return (v.y > p.y && v.y < q.y) || (v.y < p.y && v.y > q.y);
}

// The interval of [u, w] along the line of [p, q] overlaps (p, q) in a segment of positive length.
bool overlaps_along(Point u, Point w, Point p, Point q) {
  const bool by_x = std::fabs(q.x - p.x) >= std::fabs(q.y - p.y);
  auto c = [by_x](Point a) { return by_x ? a.x : a.y; };
  const double lo = std::max(std::min(c(u), c(w)), std::min(c(p), c(q)));
  const double hi = std::min(std::max(c(u), c(w)), std::max(c(p), c(q)));
  return lo < hi;
}

enum class Contact { None, Overlap, Hanging };

// How triangle t meets the open boundary edge (p, q) of a triangle lying on its left.
Contact contact(const Point t[3], Point p, Point q) {
  int o[3];
  bool left = true, right = true;
  for (int i = 0; i < 3; ++i) {
    o[i] = orient2d(p, q, t[i]);
    if (o[i] < 0) left = false;
    if (o[i] > 0) right = false;
  }
  if (!left && !right) {
    // t straddles the line: its interior meets the open segment unless one of t's edge lines has p and q on
    // its closed outer side (separating axes of a triangle and a segment).
    for (int e = 0; e < 3; ++e)
      if (orient2d(t[e], t[(e + 1) % 3], p) <= 0 && orient2d(t[e], t[(e + 1) % 3], q) <= 0) return Contact::None;
    return Contact::Overlap;
  }
  // t on one closed side: it touches the open segment at a vertex inside it, or along one of its edges.
  bool touches = false, same_edge = false;
  for (int i = 0; i < 3; ++i)
    if (o[i] == 0 && strictly_between(t[i], p, q)) touches = true;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (o[i] == 0 && o[j] == 0 && overlaps_along(t[i], t[j], p, q)) {
      touches = true;
      if ((t[i] == q && t[j] == p) || (t[i] == p && t[j] == q)) same_edge = true;
    }
  }
  if (!touches) return Contact::None;
  if (left) return Contact::Overlap;  // on the edge's own triangle's side
  return same_edge ? Contact::None : Contact::Hanging;  // a crack is allowed; a hanging vertex is not
}

}  // namespace

void check_mesh_planar(const Mesh& mesh, const FluidGrid& grid, const std::string& name,
                       const std::vector<int>* original) {
  auto id = [original](int k) { return std::to_string(original ? (*original)[k] : k); };
  std::vector<int> seen(mesh.size(), -1);
  for (int k = 0; k < mesh.size(); ++k) {
    Point corner[3];
    mesh.corners(k, corner);
    for (int i = 0; i < 3; ++i) {
      const int n = mesh.neighbours[k][i];
      if (n >= 0 && n < k) continue;  // the edge seen from n
      const Point p = corner[(i + 1) % 3], q = corner[(i + 2) % 3];
      if (n >= 0) {
        // The neighbour's vertex opposite the shared edge lies on the other side.
        for (int j = 0; j < 3; ++j)
          if (mesh.neighbours[n][j] == k && orient2d(p, q, mesh.vertex(n, j)) >= 0)
            throw Error(name + " overlaps itself: triangles " + id(k) + " and " + id(n) +
                        " lie on the same side of their shared edge");
        continue;
      }
      const Point lo{std::min(p.x, q.x), std::min(p.y, q.y)}, hi{std::max(p.x, q.x), std::max(p.y, q.y)};
      const int stamp = 3 * k + i;
      grid.for_each_in_box(lo, hi, [&](int j) {
        if (j == k || seen[j] == stamp) return;
        seen[j] = stamp;
        Point t[3];
        mesh.corners(j, t);
        const Contact c = contact(t, p, q);
        if (c == Contact::Overlap)
          throw Error(name + " overlaps itself: triangles " + id(k) + " and " + id(j) + " overlap");
        if (c == Contact::Hanging)
          throw Error(name + " is not conforming: triangle " + id(j) + " touches the inside of an edge of triangle " +
                      id(k) + " that has no neighbour (a hanging vertex)");
      });
    }
  }
}

void check_finite(const CsrMatrix& matrix, const CouplingOptions& opt) {
  // v * 0 is 0 for a finite v, NaN for NaN or Inf: sums of such terms are 0 when every value is finite (two
  // sums side by side, which the compiler pairs); otherwise the first value that is not is looked for.
  const double* v = matrix.value.data();
  const size_t n = matrix.value.size();
  double z0 = 0, z1 = 0;
  size_t i = 0;
  for (; i + 1 < n; i += 2) {
    z0 += v[i] * 0;
    z1 += v[i + 1] * 0;
  }
  if (i < n) z0 += v[i] * 0;
  if (z0 == 0 && z1 == 0) return;
  for (size_t e = 0; e < matrix.value.size(); ++e) {
    if (std::isfinite(matrix.value[e])) continue;
    const auto row = std::upper_bound(matrix.start.begin(), matrix.start.end(), static_cast<int>(e)) - matrix.start.begin() - 1;
    throw Error("the coupling overflows: entry (" + std::to_string(row) + ", " + std::to_string(matrix.column[e]) +
                ") is " + option_value(matrix.value[e]) + "; c1=" + option_value(opt.c1) + " and c2=" + option_value(opt.c2) +
                " are too large for these meshes");
  }
}

}  // namespace dlmfsi
