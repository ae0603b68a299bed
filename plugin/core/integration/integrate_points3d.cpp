#include "integration/integrate_points3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sides/report.hpp"
#include "sides/sides3d.hpp"
#include "errors.hpp"
#include "geometry/predicates3d.hpp"
#include "map/pull_back3d.hpp"
#include "fe/rules.hpp"
#include "fe/lattice3d.hpp"
#include "fe/points_evaluation3d.hpp"
#include "fe/weighted_sum.hpp"
#include "integration/reference_tet.hpp"

namespace dlmfsi {

PointIntegrator3::PointIntegrator3(const Integrand3& integrand, CouplingReport& counts, const FluidSide3* fluid)
    : integrand_(integrand), counts_(counts), fluid_functions_(static_cast<int>(integrand.fluid.functions().size())),
      gradients_(integrand.c1 != 0), listing_(integrand.c1 != 0 && !integrand.chain),
      constant_multiplier_gradients_(gradients_ && !listing_ && integrand.multiplier.fitted() &&
                                     integrand.multiplier.degree() <= 1),
      constant_fluid_gradients_(integrand.fluid.fitted() && integrand.fluid.degree() <= 1),
      polynomial_multiplier_(!listing_ && integrand.fluid.fitted() && integrand.multiplier.fitted() &&
                             integrand.multiplier.degree() <= 2),
      fluid_(fluid), values_(integrand) {}

double PointIntegrator3::integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) {
  begin_across();
  band_moments_ = false;
  const double volume = gather(image, kf, piece);
  add_gathered(image.tetrahedron, kf, block);
  if (band_moments_) add_band_moments(image, block);
  if (groups_used_ > 0) add_across(image.tetrahedron, block);
  return volume;
}

template <class Group>
Group& PointIntegrator3::group_of(int kf, std::vector<Group>& groups, int& used) {
  if (tet_stamp_[kf] == tet_epoch_) return groups[tet_group_[kf]];
  tet_stamp_[kf] = tet_epoch_;
  tet_group_[kf] = used;
  if (used == static_cast<int>(groups.size())) groups.emplace_back();
  Group& group = groups[used++];
  group.kf = kf;
  group.fresh = true;
  return group;
}

void PointIntegrator3::begin_across() {
  groups_used_ = 0;
  const size_t tets = static_cast<size_t>(fluid_ ? fluid_->mesh().size() : 0);
  if (tet_stamp_.size() != tets) {
    tet_stamp_.assign(tets, 0);
    tet_group_.assign(tets, 0);
  }
  if (++tet_epoch_ == 0) {
    std::fill(tet_stamp_.begin(), tet_stamp_.end(), 0);
    tet_epoch_ = 1;
  }
}

// Each group's points become the gathered points in turn (their vectors swapped, not copied).
void PointIntegrator3::add_across(const MappedTet& mt, LocalBlock& block) {
  for (int g = 0; g < groups_used_; ++g) {
    AcrossGroup& group = across_[g];
    eta_.swap(group.eta);
    xi_.swap(group.xi);
    weight_.swap(group.weight);
    jac_.swap(group.jac);
    block.enter_fluid_element(fluid_->dofs(group.kf));
    add_gathered(mt, group.kf, block);
    eta_.swap(group.eta);
    xi_.swap(group.xi);
    weight_.swap(group.weight);
    jac_.swap(group.jac);
  }
  groups_used_ = 0;
}

void PointIntegrator3::start_band_moments(const ClippedImage3& image, const QuadraticTerms& terms) {
  // a fluid of degree 3 or more (P1b: 35 monomials, of which its terms read a few) forms fewer products point by
  // point in each tetrahedron (curved_cost3d -fluid P1b: 3.7-4.0 ms a solid tetrahedron, 4.4-4.7 as moments)
  band_moments_ = terms.quadratic && weighted_sum_terms(image.tetrahedron) && integrand_.fluid.fitted() &&
                  integrand_.fluid.degree() <= 2;
  if (!band_moments_) return;
  column_rule_ = &line_rule(image.degree);
  moment_groups_used_ = 0;
  face_moments_.reset(integrand_.multiplier.degree(), integrand_.fluid.degree(), image.sub_xi[0]);
  beyond_moments_.reset(integrand_.multiplier.degree(), integrand_.fluid.degree(), image.sub_xi[0]);
}

void PointIntegrator3::add_column_moments(const BandFace& face, Point3 xi, Point3 x0, Point3 dd, double l,
                                          double column, PointMoments3* into) {
  PointMoments3& moments = into ? *into : face_moments_;
  const LineRule& along = *column_rule_;
  for (size_t k = 0; k < along.nodes.size(); ++k) {
    const double t = along.nodes[k] * l;
    moments.add(xi + t * face.d, x0 + (t * dd + (0.5 * t * t) * face.dhd), along.weights[k] * column);
  }
}

void PointIntegrator3::add_face_moments(const ClippedImage3& image, int kf, double sign, const PointMoments3* from) {
  const PointMoments3& moments = from ? *from : face_moments_;
  const PolynomialBasis3& fluid = integrand_.fluid;
  const size_t size = static_cast<size_t>(monomial_count3(integrand_.multiplier.degree())) *
                      static_cast<size_t>(monomial_count3(fluid.degree()));
  MomentGroup& group = group_of(kf, moment_groups_, moment_groups_used_);
  if (group.fresh) {
    group.fresh = false;
    group.points = 0;
    group.moments.assign(size, 0.0);
  }
  element_moments_.resize(size);
  moments.element_moments(fluid.to_reference(kf, moments.x_centre(), image.origin), fluid.inverse_jacobian(kf),
                          element_moments_.data());
  for (size_t i = 0; i < size; ++i) group.moments[i] += sign * element_moments_[i];
  group.points += moments.points();
}

// add_weighted_sums' terms from each fluid tetrahedron's moments.
void PointIntegrator3::add_band_moments(const ClippedImage3& image, LocalBlock& block) {
  const PolynomialBasis3& fluid = integrand_.fluid;
  const int count = monomial_count3(integrand_.multiplier.degree());
  size_weighted_terms();
  for (int g = 0; g < moment_groups_used_; ++g) {
    const MomentGroup& group = moment_groups_[g];
    counts_.points += group.points;
    block.enter_fluid_element(fluid_->dofs(group.kf));
    fluid.sums_from_moments(group.kf, group.moments.data(), count, value_terms_.data(),
                            gradients_ ? gradient_terms_.data() : nullptr);
    add_weighted_terms(image.tetrahedron, face_moments_.centre(), block);
  }
  moment_groups_used_ = 0;
}

void PointIntegrator3::add_points(const MappedTet& mt, int kf, const PointData* points, int n, LocalBlock& block) {
  clear_points();
  point_jacobians_ = true;
  for (int q = 0; q < n; ++q) {
    eta_.push_back(points[q].eta);
    xi_.push_back(points[q].xi);
    weight_.push_back(points[q].weight);
    if (!mt.affine) jac_.push_back(points[q].jac);
  }
  add_gathered(mt, kf, block);
}

void PointIntegrator3::clear_points() {
  eta_.clear();
  xi_.clear();
  weight_.clear();
  jac_.clear();
}

void PointIntegrator3::add_gathered(const MappedTet& mt, int kf, LocalBlock& block) {
  const int n = static_cast<int>(eta_.size());
  if (n == 0) return;
  counts_.points += n;
  if (weighted_sum_terms(mt)) {
    add_weighted_sums(mt, kf, n, block);
    return;
  }
  if (deferred_chain(mt)) {
    values_.evaluate_fluid_gradient_sums(kf, eta_.data(), weight_.data(), mt.k, xi_.data(), n);
  } else if (constant_chain(mt)) {
    values_.evaluate_constant_gradients(kf, eta_.data(), mt.k, xi_.data(), n);
  } else {
    values_.evaluate(kf, eta_.data(), mt.k, xi_.data(), n);
  }
  // Pairs that repeat an earlier pair's functions (on elements of the shared fits) copy its sums.
  const PolynomialBasis3 &fluid = integrand_.fluid, &multiplier = integrand_.multiplier;
  const bool twins = !listing_ && fluid.fitted() && multiplier.fitted() && fluid.shared(kf) && multiplier.shared(mt.k);
  weigh(mt, n, twins ? integrand_.pairs.fluid_read_by_sources() : integrand_.pairs.fluid_read());
  add_pairs(mt, n, twins, block);
  if (listing_) add_listing(mt, n, block);
}

double PointIntegrator3::gather(const ClippedImage3& image, int kf, const Piece3& piece) {
  if (image.reference_side) return gather_reference_side(image, kf, piece);
  point_jacobians_ = true;
  const MappedTet& mt = image.tetrahedron;
  // a polynomial integrand on an affine image; Newton's pull-backs keep the products
  const auto& rule = mt.affine ? tetrahedron_rule_for_polynomials(image.degree) : tetrahedron_rule(image.degree);
  Point3 xi_corner[Piece3::kMaxVertices];
  MapValue3 mv;
  for (int v = 0; v < piece.n; ++v)
    xi_corner[v] = mt.affine ? image.guess(piece.v[v]) : pull_back(mt, piece.v[v], image.guess(piece.v[v]), mv);
  clear_points();
  double volume = 0;
  piece.for_each_tetrahedron_index([&](int i0, int i1, int i2, int i3) {
    const Point3 tet[4] = {piece.v[i0], piece.v[i1], piece.v[i2], piece.v[i3]};
    const double vol = std::fabs(volume6(tet[0], tet[1], tet[2], tet[3])) / 6;
    volume += vol;
    const Point3 xt[4] = {xi_corner[i0], xi_corner[i1], xi_corner[i2], xi_corner[i3]};
    for (const RulePoint3& rp : rule) {
      const Point3 y = from_reference(tet, rp.xi);
      Point3 xi = from_reference(xt, rp.xi);
      double det = mt.affine_det;
      if (!mt.affine) {
        xi = pull_back(mt, y, xi, mv);
        det = det3(mv.jac);
        if (!(det > 0)) throw Error("the map folds solid tetrahedron " + std::to_string(mt.k));
        std::array<double, 9>& jac = jac_.emplace_back();
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) jac[3 * a + b] = mv.jac[a][b];
      }
      eta_.push_back(integrand_.fluid.to_reference(kf, y, image.origin));  // y relative to it
      xi_.push_back(xi);
      weight_.push_back(vol * rp.weight / det);
    }
  });
  return volume;
}

inline std::array<double, 9> PointIntegrator3::jacobian(const ClippedImage3& image, const Point3 (&d)[3]) const {
  MapValue3 mv;
  image.tetrahedron.set_jacobian(d, mv);
  std::array<double, 9> jac;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) jac[3 * a + b] = mv.jac[a][b];
  return jac;
}

inline void PointIntegrator3::add_jacobian(const ClippedImage3& image, const Point3 (&d)[3]) {
  jac_.push_back(jacobian(image, d));
}

inline void PointIntegrator3::add_across_point(int kf, Point3 eta, Point3 xi, double weight,
                                               const std::array<double, 9>& jac) {
  AcrossGroup& group = group_of(kf, across_, groups_used_);
  if (group.fresh) {
    group.fresh = false;
    group.eta.clear();
    group.xi.clear();
    group.weight.clear();
    group.jac.clear();
  }
  group.eta.push_back(eta);
  group.xi.push_back(xi);
  group.weight.push_back(weight);
  if (point_jacobians_) group.jac.push_back(jac);
}

inline void PointIntegrator3::add_reference_point(const ClippedImage3& image, int kf, Point3 xi, Point3 x,
                                                  const Point3 (&d)[3], double weight) {
  add_jacobian(image, d);
  add_reference_point(image, kf, xi, x, weight);
}

inline void PointIntegrator3::add_reference_point(const ClippedImage3& image, int kf, Point3 xi, Point3 x,
                                                  double weight) {
  add_reference_point(integrand_.fluid.to_reference(kf, x, image.origin), xi, weight);
}

inline void PointIntegrator3::add_reference_point(Point3 eta, Point3 xi, double weight) {
  eta_.push_back(eta);
  xi_.push_back(xi);
  weight_.push_back(weight);
}

namespace {

// A quadratic map over the simplex q0 + sum_k a_k q_k (k < dims, 2 or 3) of reference points, in the a_k:
// X = x + sum_k a_k lin_k + sum_(k <= m) a_k a_m quad_km (the diagonal terms halved), from X(q0), dX/dxi at
// xi = 0 (d0) and the hessian h: one evaluation of the map, then a few vector products per point.
struct OverSimplex {
  int dims = 0;
  Point3 x, lin[3], quad[3][3];
  void set(Point3 x_q0, const Point3 (&d0)[3], const double (&h)[3][3][3], Point3 q0, const Point3* q, int n) {
    auto hessian = [&h](Point3 p, Point3 r) {  // h's bilinear form, per component
      const double pp[3] = {p.x, p.y, p.z}, rr[3] = {r.x, r.y, r.z};
      double out[3] = {0, 0, 0};
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) out[a] += h[a][i][j] * pp[i] * rr[j];
      return Point3{out[0], out[1], out[2]};
    };
    dims = n;
    x = x_q0;
    for (int k = 0; k < n; ++k) {  // dX/dxi at q0 times q_k
      lin[k] = (q[k].x * d0[0] + q[k].y * d0[1] + q[k].z * d0[2]) + hessian(q[k], q0);
      for (int m = k; m < n; ++m) quad[k][m] = (m == k ? 0.5 : 1.0) * hessian(q[k], q[m]);
    }
  }
  Point3 at(const double* a) const {
    Point3 linear, quadratic;
    for (int k = 0; k < dims; ++k) {
      linear = linear + a[k] * lin[k];
      for (int m = k; m < dims; ++m) quadratic = quadratic + (a[k] * a[m]) * quad[k][m];
    }
    return x + (linear + quadratic);
  }
};

}  // namespace

double PointIntegrator3::gather_reference_side(const ClippedImage3& image, int kf, const Piece3& piece) {
  const MappedTet& mt = image.tetrahedron;
  const auto& rule = tetrahedron_rule_for_polynomials(image.degree);
  // the piece's corners taken back by the sub-tetrahedron's affine interpolant: its tetrahedra's preimages
  Point3 xi_corner[Piece3::kMaxVertices];
  for (int v = 0; v < piece.n; ++v) xi_corner[v] = image.guess(piece.v[v]);
  // ds = det [solid edges] dxi
  const double solid_det = volume6(mt.solid[0], mt.solid[1], mt.solid[2], mt.solid[3]);
  clear_points();
  // dX/ds at each point where the gradient terms read it there (not under weighted_sum_terms: add_weighted_sums forms
  // it from the points' weights and xi, dX/dxi being affine in xi)
  point_jacobians_ = gradients_ && !weighted_sum_terms(mt);
  QuadraticTerms terms;
  terms.quadratic = mt.reference_hessian(terms.hessian);
  terms.alone = terms.quadratic && !point_jacobians_;
  if (terms.alone) {
    Point3 x_corner;
    reference_value(image, Point3(), x_corner, terms.d_corner);
  }
  // X alone under a quadratic map: over each of the piece's tetrahedra from its Taylor terms (OverSimplex), where
  // the rule has enough points to pay for them
  const bool over = terms.alone && rule.size() > 10;
  OverSimplex x_over;
  double volume = 0;
  piece.for_each_tetrahedron_index([&](int i0, int i1, int i2, int i3) {
    volume += std::fabs(volume6(piece.v[i0], piece.v[i1], piece.v[i2], piece.v[i3])) / 6;
    const Point3 xt[4] = {xi_corner[i0], xi_corner[i1], xi_corner[i2], xi_corner[i3]};
    const double measure = std::fabs(volume6(xt[0], xt[1], xt[2], xt[3])) / 6 * solid_det;
    const Point3 edges[3] = {xt[1] - xt[0], xt[2] - xt[0], xt[3] - xt[0]};
    if (over) x_over.set(reference_position(image, xt[0]), terms.d_corner, terms.hessian, xt[0], edges, 3);
    for (const RulePoint3& rp : rule) {
      const Point3 xi = from_reference(xt, rp.xi);
      if (!point_jacobians_) {
        const double abc[3] = {rp.xi.x, rp.xi.y, rp.xi.z};
        add_reference_point(image, kf, xi, over ? x_over.at(abc) : reference_position(image, xi), measure * rp.weight);
        continue;
      }
      Point3 x, d[3];
      reference_value(image, xi, x, d);
      add_reference_point(image, kf, xi, x, d, measure * rp.weight);
    }
  });
  start_band_moments(image, terms);
  gather_band(image, kf, piece, xi_corner, solid_det, terms);
  note_side_piece(kf, piece);
  return volume;
}

// Where a face plane of kf holds a face of the sub-tetrahedron, the band on each side lies in that side's
// sub-tetrahedron (or outside the solid), and there is no piece of the same sub-tetrahedron across: the columns
// going into the sub-tetrahedron carry both terms (-f_K here, +f_K' of the fluid tetrahedron K' across, added by
// add_across), those going out nothing (the sub-tetrahedron across does them with its own map; beyond the solid
// there is nothing). Exact signs on the sub-tetrahedron's image corners decide.
int PointIntegrator3::fluid_plane(const ClippedImage3& image, const Point3 (&corner)[4], unsigned common,
                                  bool& on_boundary) const {
  const unsigned fluid_planes = common >> 4 & 0xFu;
  on_boundary = false;
  if (fluid_planes != 0 && !fluid_) return __builtin_ctz(fluid_planes);
  if (!fluid_) return -1;
  // orient3d of kf's face j (opposite vertex j, corners j + 1, j + 2, j + 3 mod 4) against p, signed so that
  // kf's vertex j is positive: kf is positively oriented, and (j + 1, j + 2, j + 3, j) is an odd permutation of
  // (0, 1, 2, 3) for even j, an even one for odd j
  auto side = [&corner](int j, Point3 p) {
    const int s = orient3d(corner[(j + 1) & 3], corner[(j + 2) & 3], corner[(j + 3) & 3], p);
    return j & 1 ? s : -s;
  };
  if (fluid_planes != 0) {  // on the sub-tetrahedron's boundary iff no corner of its image lies beyond the plane
    const int j = __builtin_ctz(fluid_planes);
    on_boundary = true;
    for (int i = 0; i < 4; ++i) on_boundary = on_boundary && side(j, image.sub_y[i]) >= 0;
    return j;
  }
  if ((common & 0xFu) == 0) return -1;
  // a face of the sub-tetrahedron's image (opposite its corner i): in a plane of kf? (the clip keeps one bit
  // for a plane of both)
  const int i = __builtin_ctz(common & 0xFu);
  for (int j = 0; j < 4; ++j) {
    bool all = true;
    for (int c = 1; c < 4 && all; ++c) all = side(j, image.sub_y[(i + c) & 3]) == 0;
    if (all) {
      on_boundary = true;
      return j;
    }
  }
  return -1;
}

namespace {

// j v for a row-major 3 x 3 matrix j (an element's d xi / d x).
inline Point3 linear_part(const double* j, Point3 v) {
  return {j[0] * v.x + j[1] * v.y + j[2] * v.z, j[3] * v.x + j[4] * v.y + j[5] * v.z,
          j[6] * v.x + j[7] * v.y + j[8] * v.z};
}

// The band's axis for a face whose plane's preimage has gradient z (grad_xi (n . A)): of the solid's axes (axis,
// in reference coordinates) the one with the largest |z . axis_a|, the first within 1e-9 of it (both sides of
// the face, whose n differ by a positive factor and round-off, choose the same), signed so that n . A grows
// along it by rise.
Point3 column_axis(Point3 z, const Point3 (&axis)[3], double& rise) {
  const double g[3] = {dot(z, axis[0]), dot(z, axis[1]), dot(z, axis[2])};
  const double largest = std::max({std::fabs(g[0]), std::fabs(g[1]), std::fabs(g[2])});
  const int a = std::fabs(g[0]) >= (1 - 1e-9) * largest ? 0 : std::fabs(g[1]) >= (1 - 1e-9) * largest ? 1 : 2;
  rise = std::fabs(g[a]);
  return (g[a] > 0 ? 1.0 : -1.0) * axis[a];
}

}  // namespace

Point3 PointIntegrator3::face_normal(int kf, int j) const {
  const double* inv = integrand_.fluid.inverse_jacobian(kf);  // rows: grad_x xi_1, xi_2, xi_3 of kf
  const Point3 r1{inv[0], inv[1], inv[2]}, r2{inv[3], inv[4], inv[5]}, r3{inv[6], inv[7], inv[8]};
  return j == 0 ? r1 + r2 + r3 : -1.0 * (j == 1 ? r1 : j == 2 ? r2 : r3);
}

bool PointIntegrator3::band_face(const ClippedImage3& image, int kf, int j, int across, const QuadraticTerms& terms,
                                  BandFace& face, Point3& n, double& rise, double& height) const {
  const MappedTet& mt = image.tetrahedron;
  n = face_normal(kf, j);
  // grad_xi (n . A) = E_xi^-T E_y^T n (the straight image's edges from corner 0: straight_)
  const Point3 z = straight_gradient(n);
  const double grad = std::sqrt(dot(z, z));
  if (!(grad > 0)) return false;
  const Point3 axis[3] = {mt.reference_direction(0), mt.reference_direction(1), mt.reference_direction(2)};
  // The axis is chosen from the whole solid tetrahedron's affine interpolant, so that the sub-tetrahedra's columns of
  // one plane run along one axis and tile the band across their faces (each sub-tetrahedron choosing from its own
  // straight image could pick another axis near a tie: gaps and overlaps of the band's thickness, an error algebraic
  // in the sub-tetrahedra's size); its sub-tetrahedron's own choice where the plane hardly rises along it there.
  Point3 d = column_axis(z, axis, rise);
  const StraightImage& st = straight_;
  const Point3 z_whole{dot(n, st.whole_e[0]), dot(n, st.whole_e[1]), dot(n, st.whole_e[2])};
  double rise_whole;
  const Point3 d_whole = column_axis(z_whole, axis, rise_whole);
  const double along = dot(z, d_whole);
  if (std::fabs(along) > 0.25 * rise) {
    d = (along > 0 ? 1.0 : -1.0) * d_whole;  // outward: n . A grows along d
    rise = std::fabs(along);
  }
  height = rise / grad;                         // d . nu: a column's height per unit of l
  face.d = d;
  face.quadratic = terms.quadratic;
  if (terms.quadratic) {
    for (int i = 0; i < 3; ++i) face.hd[i] = hessian_along(terms.hessian, i, d);
    face.dhd = d.x * face.hd[0] + d.y * face.hd[1] + d.z * face.hd[2];
  }
  set_face_tets(face, kf, across);
  return true;
}

void PointIntegrator3::set_face_tets(BandFace& face, int kf, int across) const {
  face.across = across;
  if (!face.quadratic) return;
  face.eta_dhd = linear_part(integrand_.fluid.inverse_jacobian(kf), face.dhd);
  if (across >= 0) face.across_dhd = linear_part(integrand_.fluid.inverse_jacobian(across), face.dhd);
}

// The band. On a face of the piece in a face plane of kf (n . y = c, n outward), the straight image's
// boundary A(xi) lies where the true one X(xi) does not: the true piece ends where q(xi) = n . X(xi) - c
// vanishes, past the face (q < 0 on it: X(xi) still inside kf) or short of it (q > 0). The band between
// them is taken in columns along one axis e_a of the solid's coordinates s (d = d xi / d s_a in each
// tetrahedron's reference coordinates), the axis along which the face plane's preimage rises most: from the
// face point xi the column reaches l, the root of q(xi + l d), a quadratic in l (a P2 map), and adds
// int_face (d . nu) int_0^l f(xi + s d) ds dA_xi (nu the face's unit normal in xi). Along the column f is a
// polynomial of the rule's degree in s (Gauss-Legendre, exact); over the face, int_0^l f is a polynomial of
// degree 2 p + 2 where l is quadratic in xi (n . X linear along d), and smooth otherwise.
// Columns along a common axis tile the region between the straight images' surface and the true one whatever the
// sub-tetrahedra and solid tetrahedra it crosses, so that a kink along one fluid plane is integrated to round-off. A
// column may go on beyond the solid tetrahedron, with its polynomials (which may kink across the face);
// the side band (side_band3d.cpp) takes that part back and adds the part of the band inside the tetrahedron that no
// column from its pieces' faces reaches. Where two fluid faces meet with jumps that do not add up, a face's columns
// charge its jump where their start lies in it, not where the segment from A to X crosses it: edge_strips corrects
// that along the face's edges (edge_strip3d.cpp); what is left is of the next order, near the corners.
// Each column adds f_K and, with the opposite sign, f_K' of the fluid tetrahedron across, at the same points: the
// band's integral of f_K - f_K', to round-off where f does not jump. Where the face is inside the sub-tetrahedron's
// image, one of the two pieces takes the columns for both; where it lies on the sub-tetrahedron's boundary, each side
// takes those going into its own, from the same face points (a fan from the face's least vertex, each triangle's
// corners in that order: order() below).
void PointIntegrator3::gather_band(const ClippedImage3& image, int kf, const Piece3& piece, const Point3* xi_corner,
                                   double solid_det, const QuadraticTerms& terms) {
  // a quadratic map along a column: X(xi + l d) = X + l D d + l^2 (d^T H d) / 2, D(xi + l d) = D + l H d; where
  // the face points take X alone, their slopes from dX/dxi = D_corner + H xi
  const bool alone = terms.alone;
  const double(&hessian)[3][3][3] = terms.hessian;
  const Point3(&D_corner)[3] = terms.d_corner;
  // The face points must not depend on the side: the pieces' vertices are not numbered in any order
  // (clip_filtered), so they are ordered by a linear function of their position in a direction that no mesh
  // is aligned with (a tie, two vertices at the same value, is then an accident of measure zero).
  const Point3 probe{0.8472130847939790, 0.3089153715245366, 0.4323690461218483};
  auto order = [&piece, probe](int v) { return dot(piece.v[v], probe); };
  // the face's rule, for int_0^l f (degree 2 p + 2 where l is quadratic; along the column, add_column's rule of
  // degree p: xi + s d is affine in s, f a polynomial of degree p in s)
  const auto& face_rule = triangle_rule_for_polynomials(std::min(60, 2 * image.degree + 2));
  Point3 corner[4];  // kf's, for fluid_plane
  if (fluid_) fluid_->mesh().corners(kf, corner);
  for (int f = 0; f < piece.faces; ++f) {
    const int s = piece.face_start[f], e = piece.face_start[f + 1];
    unsigned common = 0xFFu;
    for (int i = s; i < e; ++i) common &= piece.planes[piece.face_index[i]];
    bool on_boundary = false;
    const int j = fluid_plane(image, corner, common, on_boundary);
    if (j < 0) continue;
    // The fluid tetrahedron across. Where the sub-tetrahedron's image crosses the face plane, the piece across
    // has the same face, the same columns with the opposite sign: the one in the lower-numbered fluid tetrahedron
    // takes the columns for both (add_across adds the other's).
    const int across = fluid_ ? fluid_->mesh().neighbours[kf][j] : -1;
    if (!on_boundary && across >= 0 && across < kf) continue;
    BandFace face;
    Point3 n, dd_corner;  // dd_corner: dX/dl at xi = 0 (quadratic maps whose face points take X alone)
    double rise, height;
    if (!band_face(image, kf, j, across, terms, face, n, rise, height)) continue;
    const Point3 d = face.d;
    const Point3(&hd)[3] = face.hd;
    if (alone) dd_corner = d.x * D_corner[0] + d.y * D_corner[1] + d.z * D_corner[2];
    // the fan from the face's least vertex in order(), each triangle's other corners in that order
    int first = s;
    for (int i = s + 1; i < e; ++i) first = order(piece.face_index[i]) < order(piece.face_index[first]) ? i : first;
    const int m = e - s, v0 = piece.face_index[first];
    if (band_moments_) face_moments_.clear();
    for (int i = 1; i + 1 < m; ++i) {
      int v1 = piece.face_index[s + (first - s + i) % m], v2 = piece.face_index[s + (first - s + i + 1) % m];
      if (order(v2) < order(v1)) std::swap(v1, v2);
      const Point3 q0 = xi_corner[v0], q1 = xi_corner[v1] - q0, q2 = xi_corner[v2] - q0;
      const Point3 p0 = piece.v[v0], p1 = piece.v[v1] - p0, p2 = piece.v[v2] - p0;
      const double area = std::sqrt(dot(cross(q1, q2), cross(q1, q2))) / 2 * solid_det;
      // X alone where dX/dxi is not read: a quadratic in the triangle's coordinates, and dX/dl affine, of slope H d
      OverSimplex x_over;
      const Point3 edges[2] = {q1, q2};
      if (alone) x_over.set(reference_position(image, q0), D_corner, hessian, q0, edges, 2);
      for (const RulePoint& rp : face_rule) {
        const Point3 xi = q0 + (rp.xi.x * q1 + rp.xi.y * q2);
        const Point3 y = p0 + (rp.xi.x * p1 + rp.xi.y * p2);
        Point3 x0, D[3], dd;  // X, dX/dxi and dX/dl along the column
        if (alone) {
          const double ab[2] = {rp.xi.x, rp.xi.y};
          x0 = x_over.at(ab);
          dd = dd_corner + (xi.x * hd[0] + xi.y * hd[1] + xi.z * hd[2]);
        } else {
          reference_value(image, xi, x0, D);
          dd = d.x * D[0] + d.y * D[1] + d.z * D[2];
        }
        const double root = column_root(image, face, n, y, xi, x0, dd, rise);
        if (root == 0) continue;
        if (on_boundary && !(root < 0)) continue;
        if (band_moments_)
          add_column_moments(face, xi, x0, dd, root, root * height * area * rp.weight);
        else
          add_column(image, kf, face, xi, x0, dd, D, root, root * height * area * rp.weight);
      }
    }
    if (!on_boundary && fluid_) edge_strips(image, kf, j, piece, f, xi_corner, solid_det, face, n, rise, height);
    if (!band_moments_) continue;
    face_moments_.settle();
    if (face_moments_.points() == 0) continue;
    add_face_moments(image, kf, 1);  // f_K in kf, -f_K' in the tetrahedron across (add_column's)
    if (across >= 0) add_face_moments(image, across, -1);
  }
}

// Along a quadratic map's column X(xi + t d) = x0 + t dd + t^2 dhd / 2 and dX/dxi = D + t H d; the fluid
// elements' reference coordinates are affine in X, so they follow the same way from their value and slope at t = 0.
void PointIntegrator3::add_column(const ClippedImage3& image, int kf, const BandFace& face, Point3 xi, Point3 x0,
                                  Point3 dd, const Point3 (&D)[3], double l, double column, int near) {
  const int own = kf;
  if (near >= 0) kf = near;
  const PolynomialBasis3& fluid = integrand_.fluid;
  const LineRule& along = line_rule(image.degree);
  const int across = face.across;
  Point3 eta0, eta1, across0, across1;  // at t = 0 and d/dt, in kf and in the fluid tetrahedron across
  if (face.quadratic) {
    eta0 = fluid.to_reference(kf, x0, image.origin);
    eta1 = linear_part(fluid.inverse_jacobian(kf), dd);
    if (across >= 0) {
      across0 = fluid.to_reference(across, x0, image.origin);
      across1 = linear_part(fluid.inverse_jacobian(across), dd);
    }
  }
  for (size_t k = 0; k < along.nodes.size(); ++k) {
    const double t = along.nodes[k] * l, weight = along.weights[k] * column;
    const Point3 at = xi + t * face.d;
    Point3 xt, Dt[3];  // X there (maps that are not quadratic), and dX/dxi where the points carry it
    if (face.quadratic) {
      if (point_jacobians_)
        for (int c = 0; c < 3; ++c) Dt[c] = D[c] + t * face.hd[c];
    } else if (point_jacobians_) {
      reference_value(image, at, xt, Dt);
    } else {
      xt = reference_position(image, at);
    }
    std::array<double, 9> jac{};
    if (point_jacobians_) jac = jacobian(image, Dt);
    const double h = 0.5 * t * t;
    const Point3 eta =
        face.quadratic ? eta0 + t * eta1 + h * face.eta_dhd : fluid.to_reference(kf, xt, image.origin);
    if (kf == own) {
      if (point_jacobians_) jac_.push_back(jac);
      add_reference_point(eta, at, weight);
    } else {  // the column's own tetrahedron is not the piece's: with the points of the tetrahedra across
      add_across_point(kf, eta, at, weight, jac);
    }
    if (across >= 0)
      add_across_point(across,
                       face.quadratic ? across0 + t * across1 + h * face.across_dhd
                                      : fluid.to_reference(across, xt, image.origin),
                       at, -weight, jac);
  }
}

void PointIntegrator3::weigh(const MappedTet& mt, int n, const std::vector<char>& read) {
  const double(&aj)[3][3] = mt.affine_value.jac;
  const bool deferred = deferred_chain(mt), constant = constant_chain(mt), gradients = gradients_ && !listing_;
  if (constant_multiplier_gradients_) gradient_sums_.resize(3 * static_cast<size_t>(fluid_functions_));
  double jw[9] = {};  // constant chain: c1 sum_q w_q J_q
  if (constant) jacobian_sum(n, jw);
  for (int f = 0; f < fluid_functions_; ++f) {
    if (!read[f]) continue;
    double* v = values_.fluid_value(f);
    for (int q = 0; q < n; ++q) v[q] *= integrand_.c2 * weight_[q];
    if (!gradients) continue;
    double* sums = constant_multiplier_gradients_ ? &gradient_sums_[3 * static_cast<size_t>(f)] : nullptr;
    if (deferred) {
      // c1 J^T sum_q w_q grad phi(q), J = dX/ds constant, from the evaluation's weighted sums
      const double* d = values_.fluid_gradient_sum(f);
      for (int b = 0; b < 3; ++b) sums[b] = integrand_.c1 * (d[0] * aj[0][b] + d[1] * aj[1][b] + d[2] * aj[2][b]);
      continue;
    }
    if (constant) {  // (c1 sum_q w_q J_q)^T grad phi, grad phi constant
      const double* d = values_.fluid_constant_gradient(f);
      for (int b = 0; b < 3; ++b) sums[b] = d[0] * jw[b] + d[1] * jw[3 + b] + d[2] * jw[6 + b];
      continue;
    }
    double* const gradient = values_.fluid_gradient(f);
    double* g[3] = {gradient, gradient + n, gradient + 2 * n};
    double s[3] = {0, 0, 0};
    for (int q = 0; q < n; ++q) {
      const double w = weight_[q];
      const double* jq = mt.affine ? &aj[0][0] : jac_[q].data();
      const double d0 = g[0][q], d1 = g[1][q], d2 = g[2][q];
      for (int b = 0; b < 3; ++b) {
        const double gb = integrand_.c1 * w * (d0 * jq[b] + d1 * jq[3 + b] + d2 * jq[6 + b]);
        if (sums) s[b] += gb;
        else g[b][q] = gb;
      }
    }
    if (sums) std::copy(s, s + 3, sums);
  }
}

void PointIntegrator3::jacobian_sum(int n, double (&jw)[9]) const {
  for (int q = 0; q < n; ++q)
    for (int i = 0; i < 9; ++i) jw[i] += weight_[q] * jac_[q][i];
  for (double& v : jw) v *= integrand_.c1;
}

void PointIntegrator3::chain_matrices(const MappedTet& mt, Point3 xi, MapValue3& j0, MapValue3 (&g)[3]) const {
  double h[3][3][3];
  mt.reference_hessian(h);
  Point3 x0, d[3];
  mt.reference_derivatives(xi, x0, d);
  mt.set_jacobian(d, j0);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) d[i] = {h[0][i][j], h[1][i][j], h[2][i][j]};
    mt.set_jacobian(d, g[j]);
  }
}

namespace {

// r^e for a small integer e >= 0.
inline double power(double r, int e) {
  double out = 1;
  for (int k = 0; k < e; ++k) out *= r;
  return out;
}

// The polynomials coef (monomial_count3(degree) coefficients each, in xi, lattice3d.hpp's order) about c:
// out[count f + g] is the coefficient of (xi - c)^g of function f, from (c + r)^a = sum_(g <= a) binom(a, g)
// c^(a - g) r^g coordinate by coordinate.
void taylor_coefficients(const double* coef, int degree, std::size_t width, Point3 c, double* out) {
  const int count = monomial_count3(degree);
  static const double binomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  std::fill(out, out + count * width, 0.0);
  for (int m = 0; m < count; ++m) {
    int a[3];
    monomial_exponents3(m, a[0], a[1], a[2]);
    for (int gx = 0; gx <= a[0]; ++gx)
      for (int gy = 0; gy <= a[1]; ++gy)
        for (int gz = 0; gz <= a[2]; ++gz) {
          const double factor = binomial[a[0]][gx] * power(c.x, a[0] - gx) * binomial[a[1]][gy] *
                                power(c.y, a[1] - gy) * binomial[a[2]][gz] * power(c.z, a[2] - gz);
          const int g = monomial_index3(gx, gy, gz);
          for (std::size_t f = 0; f < width; ++f) out[count * f + g] += factor * coef[count * f + m];
        }
  }
}

// c2 sum_g A_g V_g + sum_g u_g . P_g for one multiplier function (tb: A, ub: u) and one fluid function (v: V,
// p: P), count monomials g; pair_term<C> the same sums in the same order with count C known.
inline double pair_term(int count, const double* tb, const double* v, const double* ub, const double* p, double c2,
                        bool gradients) {
  double mass = 0;
  for (int g = 0; g < count; ++g) mass += tb[g] * v[g];
  double sum = c2 * mass;
  if (gradients)
    for (int g = 0; g < 3 * count; ++g) sum += ub[g] * p[g];
  return sum;
}
template <int C>
inline double pair_term(const double* tb, const double* v, const double* ub, const double* p, double c2,
                        bool gradients) {
  return pair_term(C, tb, v, ub, p, c2, gradients);
}

}  // namespace

// About a point c of the batch (its first: the terms below are then of the points' spread, not of the
// tetrahedron's size, and cancel less), r = xi - c, with the weights W_g = w r^g (the monomials of degree <= m,
// the multiplier's degree), V_g(phi) = sum_q W_g(q) phi(q) and P_g(phi) = sum_q W_g(q) grad_y phi(q):
//   sum_q w psi phi = sum_g A_g V_g, psi = sum_g A_g r^g its Taylor form about c,
//   sum_q w grad_s psi . (dX/ds^T grad_y phi) = sum_q w (dX/ds grad_s psi) . grad_y phi = sum_g u_g . P_g,
// where dX/ds grad_s psi = (J(c) + sum_j r_j G_j) K^T grad_xi psi (K = dxi/ds) = sum_g u_g r^g, a polynomial of
// degree m in r. The same rule as point by point, regrouped.
void PointIntegrator3::add_weighted_sums(const MappedTet& mt, int kf, int n, LocalBlock& block) {
  const int degree = integrand_.multiplier.degree(), count = monomial_count3(degree);
  const size_t nn = static_cast<size_t>(n), cc = count;
  if (sum_weights_.size() < cc * nn) sum_weights_.resize(cc * nn);
  size_weighted_terms();
  const Point3 c = xi_[0];
  double* w = sum_weights_.data();
  // W_g = w r^g, r = xi - c
  sum_points_.resize(nn);
  for (int q = 0; q < n; ++q) sum_points_[q] = xi_[q] - c;
  weighted_monomial_rows3(degree, sum_points_.data(), weight_.data(), nn, w);
  integrand_.fluid.weighted_sums(kf, eta_.data(), w, count, n, value_terms_.data(),
                                 gradients_ ? gradient_terms_.data() : nullptr);
  add_weighted_terms(mt, c, block);
}

void PointIntegrator3::size_weighted_terms() {
  const size_t nf = static_cast<size_t>(fluid_functions_), cc = monomial_count3(integrand_.multiplier.degree());
  const size_t ns = integrand_.multiplier.functions().size();
  value_terms_.resize(cc * (nf + ns));
  gradient_terms_.resize(3 * cc * (nf + ns));
}

void PointIntegrator3::add_weighted_terms(const MappedTet& mt, Point3 c, LocalBlock& block) {
  const PolynomialBasis3& multiplier = integrand_.multiplier;
  const int degree = multiplier.degree(), count = monomial_count3(degree);
  const size_t nf = static_cast<size_t>(fluid_functions_), cc = count;
  const size_t ns = multiplier.functions().size();
  double* vs = value_terms_.data();     // V_g of fluid function f at count f + g
  double* taylor = vs + cc * nf;      // A_g of multiplier function b at count b + g
  double* ps = gradient_terms_.data();  // P_g of f at 3 (count f + g)
  double* u = ps + 3 * cc * nf;       // c1 u_g of b at 3 (count b + g)
  const bool formed = terms_k_ == mt.k && terms_c_ == c;
  terms_k_ = mt.k;
  terms_c_ = c;
  if (!formed) taylor_coefficients(multiplier.coefficients(mt.k), degree, ns, c, taylor);
  if (gradients_ && !formed) {
    MapValue3 jc, gj[3];
    chain_matrices(mt, c, jc, gj);
    const double* k = multiplier.inverse_jacobian(mt.k);  // k[3 i + j] = dxi_i / ds_j
    std::fill(u, u + 3 * cc * ns, 0.0);
    for (size_t b = 0; b < ns; ++b)
      for (int g = 0; g < count; ++g) {
        // the coefficient of r^h in d psi / d xi_i is (h_i + 1) A_(h + e_i), here with h + e_i = g
        int e[3];
        monomial_exponents3(g, e[0], e[1], e[2]);
        double grad_xi[3] = {0, 0, 0};  // of r^h in grad_xi psi, h = g - e_i (g_i > 0)
        for (int i = 0; i < 3; ++i) {
          if (e[i] == 0) continue;
          int h[3] = {e[0], e[1], e[2]};
          --h[i];
          const int hi = monomial_index3(h[0], h[1], h[2]);
          std::fill(grad_xi, grad_xi + 3, 0.0);
          grad_xi[i] = e[i] * taylor[cc * b + g];
          // grad_s = K^T grad_xi; then J(c) grad_s to r^h, G_j grad_s to r^(h + e_j)
          double grad_s[3];
          for (int a = 0; a < 3; ++a) grad_s[a] = k[3 * i + a] * grad_xi[i];
          auto add = [&](const MapValue3& m, int to) {
            if (to < 0) return;
            double* out = u + 3 * (cc * b + to);
            for (int a = 0; a < 3; ++a)
              out[a] += integrand_.c1 * (m.jac[a][0] * grad_s[0] + m.jac[a][1] * grad_s[1] + m.jac[a][2] * grad_s[2]);
          };
          add(jc, hi);
          for (int j = 0; j < 3; ++j) {
            int t[3] = {h[0], h[1], h[2]};
            ++t[j];
            add(gj[j], t[0] + t[1] + t[2] <= degree ? monomial_index3(t[0], t[1], t[2]) : -1);
          }
        }
      }
  }
  const double c2 = integrand_.c2;
  const ComponentPairs& pairs = integrand_.pairs;
  for (size_t pi = 0; pi < pairs.size(); ++pi) {
    const ComponentPair& pair = pairs[pi];
    for (size_t a = 0; a < pair.fluid_functions.size(); ++a) {
      const size_t f = static_cast<size_t>(pair.fluid_functions[a]);
      const double* v = vs + cc * f;
      const double* p = ps + 3 * cc * f;
      double* col = block.column(pair.fluid_first + static_cast<int>(a)) + pair.solid_first;
      for (size_t i = 0; i < pair.solid_functions.size(); ++i) {
        const size_t b = static_cast<size_t>(pair.solid_functions[i]);
        const double *tb = taylor + cc * b, *ub = u + 3 * cc * b;
        col[i] += count == 4 ? pair_term<4>(tb, v, ub, p, c2, gradients_)  // a P1 multiplier: the loops unrolled
                             : pair_term(count, tb, v, ub, p, c2, gradients_);
      }
    }
  }
}

void PointIntegrator3::add_pairs(const MappedTet& mt, int n, bool twins, LocalBlock& block) {
  const ComponentPairs& pairs = integrand_.pairs;
  // The chain rule's gradient term: grad psi . g summed along the points (g: the weighted chain-rule
  // gradients weigh formed); with grad psi constant on the tetrahedron (a multiplier fitted at degree 0 or
  // 1), grad psi . (sum_q g_q), the sums weigh formed.
  const bool deferred = deferred_chain(mt) || constant_chain(mt);  // the multiplier's gradients at one point
  // With gradients at the points, their sums over the three components are products of rows of 3 n values.
  const bool point_gradients = gradients_ && !listing_ && !constant_multiplier_gradients_;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ComponentPair& pair = pairs[p];
    if (twins && pair.source >= 0) continue;  // added with its source
    const std::vector<int>&fi = pair.fluid_functions, &si = pair.solid_functions;
    const int na = static_cast<int>(fi.size()), nb = static_cast<int>(si.size());
    rows_.resize(2 * static_cast<size_t>(na + nb));
    const double** phi = rows_.data();
    const double** psi = phi + na;
    const double** gphi = psi + nb;
    const double** gpsi = gphi + na;
    for (int a = 0; a < na; ++a) {
      phi[a] = values_.fluid_value(fi[a]);
      // with constant multiplier gradients only the sums are read (deferred: the gradients are not formed)
      if (point_gradients) gphi[a] = values_.fluid_gradient(fi[a]);
    }
    for (int b = 0; b < nb; ++b) {
      psi[b] = values_.multiplier_value(si[b]);
      if (point_gradients) gpsi[b] = values_.multiplier_gradient(si[b]);
    }
    products_.resize(2 * static_cast<size_t>(na) * nb);
    double* value = products_.data();
    double* gradient = value + static_cast<size_t>(na) * nb;
    row_products(phi, na, psi, nb, n, value);
    if (point_gradients) row_products(gphi, na, gpsi, nb, 3 * n, gradient);
    for (int a = 0; a < na; ++a) {
      double* col = block.column(pair.fluid_first + a) + pair.solid_first;
      for (int b = 0; b < nb; ++b) {
        double sum = value[a * nb + b];
        if (point_gradients) {
          sum += gradient[a * nb + b];
        } else if (gradients_ && !listing_) {
          // grad psi constant on the tetrahedron: grad psi . (sum_q g_q), the sums weigh formed
          const double* g = &gradient_sums_[3 * static_cast<size_t>(fi[a])];
          const double* gs =
              deferred ? values_.multiplier_constant_gradient(si[b]) : values_.multiplier_gradient(si[b]);
          const int stride = deferred ? 1 : n;  // deferred: the multiplier's gradients at one point
          sum += gs[0] * g[0] + gs[stride] * g[1] + gs[2 * stride] * g[2];
        }
        col[b] += sum;
        if (twins)
          for (int copy : pair.copies) block.column(pairs[copy].fluid_first + a)[pairs[copy].solid_first + b] += sum;
      }
    }
  }
}

// The printed listings' reversed product, Grad(X,Y,Z) * Grad(u,v,w): pair index = vector component.
void PointIntegrator3::add_listing(const MappedTet& mt, int n, LocalBlock& block) {
  const double(&aj)[3][3] = mt.affine_value.jac;
  const ComponentPairs& pairs = integrand_.pairs;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      for (size_t ia = 0; ia < pairs[c].fluid_functions.size(); ++ia) {
        const double* gphi = values_.fluid_gradient(pairs[c].fluid_functions[ia]);
        // the column of pair c's ia-th fluid dof, from pair a's first multiplier dof on
        double* col = block.column(pairs[c].fluid_first + static_cast<int>(ia)) + pairs[a].solid_first;
        for (size_t ib = 0; ib < pairs[a].solid_functions.size(); ++ib) {
          const double* gpsi = values_.multiplier_gradient(pairs[a].solid_functions[ib]);
          double sum = 0;
          for (int q = 0; q < n; ++q) {
            const double jac = mt.affine ? aj[a][c] : jac_[q][3 * a + c];
            sum += integrand_.c1 * weight_[q] * jac *
                   (gpsi[q] * gphi[q] + gpsi[n + q] * gphi[n + q] + gpsi[2 * n + q] * gphi[2 * n + q]);
          }
          col[ib] += sum;
        }
      }
}

}  // namespace dlmfsi
