#include "coupling3d.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <thread>

#include "errors.hpp"
#include "predicates3d.hpp"
#include "rules.hpp"
#include "validation.hpp"

namespace dlmfsi {

std::string CouplingReport3::summary() const {
  char s[512];
  std::snprintf(s, sizeof s,
                "dlmfsi: %ld solid tetrahedra (%ld affine, %ld planar, %ld curved), %ld pieces, %ld points, "
                "degrees fluid %d multiplier %d rule %d/%d, image volume %.6g, outside %.3g, %.3f s "
                "(setup %.3f, pieces %.3f, matrix %.3f)",
                solid_tetrahedra, affine, planar, curved, pieces, points, fluid_degree, solid_degree, rule_degree,
                curved_rule_degree, image_volume, outside_volume, seconds, setup_seconds, pieces_seconds,
                seconds - setup_seconds - pieces_seconds);
  return s;
}

namespace {

struct Range {
  int first, last;
};

// The local dofs that carry the listed components.
std::vector<int> used_dofs(const Basis3& basis, const std::vector<int>& components) {
  std::vector<int> dofs;
  for (int c : components) {
    int first, last;
    basis.component_dofs(c, first, last);
    for (int d = first; d < last; ++d) dofs.push_back(d);
  }
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

// The positions, in the fitted functions' list, of component c's functions on local dofs [first, last).
std::vector<int> index_in(const std::vector<int>& functions, int c, int nc, Range dofs) {
  std::vector<int> out;
  for (int d = dofs.first; d < dofs.last; ++d)
    out.push_back(static_cast<int>(std::find(functions.begin(), functions.end(), d * nc + c) - functions.begin()));
  return out;
}

// Volume, centroid and central second moments M = int_P (y - c)(y - c)^T dy of a piece, from its
// tetrahedra: with vertices 0, a, b, c relative to the piece's first vertex, a tetrahedron of volume V has
// int y = V (a + b + c) / 4 and int y y^T = V / 20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
struct Moments {
  double volume = 0;
  Point3 centroid;
  double m[3][3] = {};
};

Moments moments(const Piece3& piece) {
  Moments out;
  const Point3 o = piece.v[0];
  double first[3] = {0, 0, 0}, second[3][3] = {};
  piece.for_each_tetrahedron([&](Point3, Point3 p, Point3 q, Point3 r) {
    const Point3 a = p - o, b = q - o, c = r - o, s = a + b + c;
    const double v = std::fabs(dot(a, cross(b, c))) / 6;
    out.volume += v;
    const double sv[3] = {s.x, s.y, s.z}, av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z}, cv[3] = {c.x, c.y, c.z};
    for (int i = 0; i < 3; ++i) {
      first[i] += v * sv[i] / 4;
      for (int j = 0; j < 3; ++j) second[i][j] += v / 20 * (av[i] * av[j] + bv[i] * bv[j] + cv[i] * cv[j] + sv[i] * sv[j]);
    }
  });
  if (!(out.volume > 0)) return out;
  const double c[3] = {first[0] / out.volume, first[1] / out.volume, first[2] / out.volume};
  out.centroid = o + Point3{c[0], c[1], c[2]};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.m[i][j] = second[i][j] - out.volume * c[i] * c[j];
  return out;
}

using Tet = std::array<Point3, 4>;

// The reference tetrahedron refined `level` times by the red rule (each tetrahedron into its four corner
// tetrahedra and the four of its inner octahedron, split along one diagonal): 8^level positive tetrahedra.
const std::vector<Tet>& reference_subdivision(int level) {
  static const auto table = [] {
    std::vector<std::vector<Tet>> all(5);
    all[0] = {Tet{Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0, 0, 1}}};
    for (int l = 1; l < 5; ++l)
      for (const Tet& t : all[l - 1]) {
        auto mid = [&](int i, int j) { return 0.5 * (t[i] + t[j]); };
        const Point3 m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3), m23 = mid(2, 3);
        const Tet children[8] = {{t[0], m01, m02, m03}, {m01, t[1], m12, m13}, {m02, m12, t[2], m23},
                                 {m03, m13, m23, t[3]}, {m01, m02, m03, m13}, {m01, m02, m12, m13},
                                 {m02, m03, m13, m23}, {m02, m12, m13, m23}};
        for (Tet c : children) {
          if (volume6(c[0], c[1], c[2], c[3]) < 0) std::swap(c[2], c[3]);
          all[l].push_back(c);
        }
      }
    return all;
  }();
  return table[level];
}

// Everything one thread needs to assemble a run of solid tetrahedra.
class Assembler3 {
 public:
  Assembler3(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map, const CouplingOptions& opt,
             const CouplingReport3& degrees)
      : fluid_(fluid), solid_(solid), map_(map), opt_(opt), search_(fluid.grid()), fpoly_(fluid.basis()),
        spoly_(solid.basis()), nf_(fluid.space().local_dofs()), ns_(solid.space().local_dofs()),
        ncf_(fluid.space().components()), ncs_(solid.space().components()) {
    report.fluid_degree = degrees.fluid_degree;
    report.solid_degree = degrees.solid_degree;
    report.rule_degree = degrees.rule_degree;
    fluid_used_ = used_dofs(fluid.space(), opt.fluid_components);
    solid_used_ = used_dofs(solid.space(), opt.solid_components);
    gradients_ = opt.c1 != 0;
    listing_ = gradients_ && opt.gradient == CouplingOptions::Gradient::Listing;
    const size_t np = opt.fluid_components.size();
    for (size_t p = 0; p < np; ++p) {
      Range f, s;
      fluid.space().component_dofs(opt.fluid_components[p], f.first, f.last);
      solid.space().component_dofs(opt.solid_components[p], s.first, s.last);
      frange_.push_back(f);
      srange_.push_back(s);
      pair_fluid_.push_back(index_in(fpoly_.functions(), opt.fluid_components[p], ncf_, f));
      pair_solid_.push_back(index_in(spoly_.functions(), opt.solid_components[p], ncs_, s));
    }
    fwidth_ = static_cast<int>(fpoly_.functions().size());
    swidth_ = static_cast<int>(spoly_.functions().size());
    linear_ = fpoly_.fitted() && spoly_.fitted() && fpoly_.degree() <= 1 && spoly_.degree() <= 1 && !listing_;
    find_pair_twins();
    sdofs_.resize(ns_);
    fcol_.resize(nf_);
  }

  void run(const int* first, const int* last) {
    for (const int* k = first; k != last; ++k) solid_tetrahedron(*k);
  }

  std::vector<Triplet> triplets;
  CouplingReport3 report;

 private:
  void solid_tetrahedron(int ks) {
    MappedTet mt;
    mt.prepare(solid_.mesh(), map_, ks);
    solid_.space().dofs(ks, sdofs_.data());
    columns_.clear();
    ++report.solid_tetrahedra;
    (mt.affine ? report.affine : (mt.planar ? report.planar : report.curved))++;
    // Curved faces: the reference tetrahedron refined, corners mapped by the true map; on each
    // sub-tetrahedron the jacobian varies 2^level times less.
    const int level = mt.planar ? 0 : (opt_.subdivide >= 0 ? opt_.subdivide : 2);
    const int degree = rule_degree(mt, std::ldexp(1.0, -level), !mt.planar);
    double outside = 0;
    if (mt.planar) {
      outside = clip_image(mt, mt.image, degree);
    } else {
      for (const Tet& sub : reference_subdivision(level)) {
        Point3 img[4];
        for (int i = 0; i < 4; ++i) {
          img[i] = mt.at(sub[i]).x;
          if (!std::isfinite(img[i].x) || !std::isfinite(img[i].y) || !std::isfinite(img[i].z))
            throw Error("the map is NaN or Inf inside solid tetrahedron " + std::to_string(ks));
        }
        outside += clip_image(mt, img, degree);
      }
    }
    report.image_volume += std::fabs(volume6(mt.image[0], mt.image[1], mt.image[2], mt.image[3])) / 6;
    outside = std::max(outside, 0.0);
    report.outside_volume += outside;
    if (outside > report.worst_outside) {
      report.worst_outside = outside;
      report.worst_tetrahedron = ks;
    }
    // Entries never touched stay exactly zero (a multiplier component paired with another fluid component).
    for (int i : solid_used_)
      for (size_t c = 0; c < columns_.size(); ++c)
        if (block_[c * ns_ + i] != 0.0) triplets.push_back({sdofs_[i], columns_[c], block_[c * ns_ + i]});
  }

  // The rule for tetrahedron mt: exact for the product's degree p when the map is affine there. Otherwise
  // the integrand in fluid coordinates, f(X^-1(y)) / det grad X, is smooth but not polynomial; its error
  // under a rule of degree p + q falls like (d/3)^q, d the map's nonlinearity (how far grad X strays from
  // the affine jacobian, map3d.hpp; measured on P1b maps, d = 0.05 to 0.4, where q = 14 gives 1e-12 at
  // d = 0.37). So q = 12 / -log10(d/3), at most 16, for an error about 1e-12 on planar images; on curved
  // images, whose error is the band between the curved boundary and the facets (1e-3 to 1e-6), 1e-8
  // (qforder overrides). scale: the jacobian's variation on a sub-tetrahedron relative to the whole.
  int rule_degree(const MappedTet& mt, double scale, bool curved) {
    if (mt.affine) return report.rule_degree;
    if (opt_.qforder >= 0) return opt_.qforder;
    const double d = std::max(scale * mt.nonlinearity, 1e-300) / 3;
    const double digits = curved ? 8 : 12;
    const int q = d >= 0.5 ? 16 : std::min(16, std::max(2, static_cast<int>(std::ceil(digits / -std::log10(d)))));
    const int degree = std::min(40, report.rule_degree + q);
    report.curved_rule_degree = std::max(report.curved_rule_degree, degree);
    return degree;
  }

  // Clips the straight tetrahedron img (the image, or a sub-tetrahedron's) against the fluid and integrates
  // the pieces; returns the volume of img outside the fluid mesh.
  double clip_image(const MappedTet& mt, const Point3 img[4], int degree) {
    const int o = orient3d(img[0], img[1], img[2], img[3]);
    if (o <= 0)
      throw Error("the map folds solid tetrahedron " + std::to_string(mt.k) + " (a sub-tetrahedron's image is " +
                  (o == 0 ? "flat)" : "negatively oriented)"));
    double covered = 0;
    search_.for_each_piece(img, hint_, [&](int kf, const Piece3& piece) {
      ++report.pieces;
      fluid_columns(kf);
      if (linear_ && mt.affine) {
        covered += integrate_linear(mt, kf, piece);
      } else {
        covered += integrate_rule(mt, kf, piece, degree);
      }
    });
    return volume6(img[0], img[1], img[2], img[3]) / 6 - covered;
  }

  // Both bases of degree <= 1 and X affine: on the piece P (volume V, centroid c, central second moments M)
  // a product of two affine functions integrates as int_P f g dy = V f(c) g(c) + grad f . M grad g, and a
  // product of gradients is constant. With y = X(s), ds = dy / det dX/ds and psi's gradient in y
  // (dX/ds)^-T grad_s psi, the block gets
  //   (c2 / det) [V phi_j(c) psi_i(c) + grad phi_j . M grad_y psi_i] + c1 (V / det) grad_s psi_i . (dX/ds^T grad phi_j).
  // Returns V.
  double integrate_linear(const MappedTet& mt, int kf, const Piece3& piece) {
    const Moments mo = moments(piece);
    report.points += 1;
    if (!(mo.volume > 0)) return 0;
    double fv[kLinear], fg[3 * kLinear], sv[kLinear], sg[3 * kLinear];
    fpoly_.evaluate_affine(kf, fpoly_.to_reference(kf, mo.centroid), fv, fg);
    spoly_.evaluate_affine(mt.k, mt.affine_reference(mo.centroid), sv, sg);
    const double(&j)[3][3] = mt.affine_value.jac;
    const double det = mt.affine_det, mass = opt_.c2 / det, stiff = opt_.c1 * mo.volume / det;
    // per solid function: its gradient in y, J^-T grad_s psi (J^-T = cofactor matrix / det)
    double sy[3 * kLinear];
    const double cof[3][3] = {{j[1][1] * j[2][2] - j[1][2] * j[2][1], j[1][2] * j[2][0] - j[1][0] * j[2][2], j[1][0] * j[2][1] - j[1][1] * j[2][0]},
                              {j[0][2] * j[2][1] - j[0][1] * j[2][2], j[0][0] * j[2][2] - j[0][2] * j[2][0], j[0][1] * j[2][0] - j[0][0] * j[2][1]},
                              {j[0][1] * j[1][2] - j[0][2] * j[1][1], j[0][2] * j[1][0] - j[0][0] * j[1][2], j[0][0] * j[1][1] - j[0][1] * j[1][0]}};
    for (int f = 0; f < swidth_; ++f)
      for (int a = 0; a < 3; ++a)  // (J^-T g)_a = sum_b (J^-1)_ba g_b, J^-1 = cof^T / det
        sy[3 * f + a] = (cof[a][0] * sg[3 * f] + cof[a][1] * sg[3 * f + 1] + cof[a][2] * sg[3 * f + 2]) / det;
    // per fluid function: c2/det (V phi(c), M grad phi) and c1 V / det J^T grad phi
    double fa[kLinear], fm[3 * kLinear], fc[3 * kLinear];
    for (int f = 0; f < fwidth_; ++f) {
      const double* g = fg + 3 * f;
      fa[f] = mass * mo.volume * fv[f];
      for (int a = 0; a < 3; ++a) {
        fm[3 * f + a] = mass * (mo.m[a][0] * g[0] + mo.m[a][1] * g[1] + mo.m[a][2] * g[2]);
        fc[3 * f + a] = stiff * (g[0] * j[0][a] + g[1] * j[1][a] + g[2] * j[2][a]);
      }
    }
    for (size_t p = 0; p < pair_fluid_.size(); ++p) {
      const std::vector<int>&fi = pair_fluid_[p], &si = pair_solid_[p];
      for (size_t a = 0; a < fi.size(); ++a) {
        const int f = fi[a];
        double* col = pair_column(p, a);
        for (size_t b = 0; b < si.size(); ++b) {
          const int g = si[b];
          double sum = fa[f] * sv[g] + fm[3 * f] * sy[3 * g] + fm[3 * f + 1] * sy[3 * g + 1] + fm[3 * f + 2] * sy[3 * g + 2];
          if (gradients_) sum += fc[3 * f] * sg[3 * g] + fc[3 * f + 1] * sg[3 * g + 1] + fc[3 * f + 2] * sg[3 * g + 2];
          col[b] += sum;
        }
      }
    }
    return mo.volume;
  }

  // A rule on each tetrahedron of the piece: the points with their reference coordinates in the fluid
  // element (eta, affine in y) and in the solid element (xi: the affine pull-back, or Newton's from the
  // interpolation of the piece's corners' pull-backs), both bases evaluated on all points at once, then
  //   block_ij += sum_q w_q [c2 psi_i phi_j + c1 grad_s psi_i . (J^T grad phi_j)],  w_q = volume weight / det J.
  // Returns the piece's volume.
  double integrate_rule(const MappedTet& mt, int kf, const Piece3& piece, int degree) {
    const auto& rule = tetrahedron_rule(mt.affine ? report.rule_degree : degree);
    Point3 xi_corner[Piece3::kMaxVertices];
    MapValue3 mv;
    for (int v = 0; v < piece.n; ++v)
      xi_corner[v] = mt.affine ? mt.affine_reference(piece.v[v]) : mt.pull_back(piece.v[v], mt.affine_reference(piece.v[v]), mv);
    points_.clear();
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
        std::array<double, 9> jac{};
        if (!mt.affine) {
          xi = mt.pull_back(y, xi, mv);
          det = det3(mv.jac);
          if (!(det > 0)) throw Error("the map folds solid tetrahedron " + std::to_string(mt.k));
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) jac[3 * a + b] = mv.jac[a][b];
        }
        points_.push_back({fpoly_.to_reference(kf, y), xi, vol * rp.weight / det, jac});
      }
    });
    const int n = static_cast<int>(points_.size());
    report.points += n;
    evaluate_points(kf, mt, n);
    // Pairs that repeat an earlier pair's functions (on elements of the shared fits) copy its sums.
    const bool twins = !listing_ && fpoly_.fitted() && spoly_.fitted() && fpoly_.shared(kf) && spoly_.shared(mt.k);
    const std::vector<char>& used = twins ? fluid_used_by_sources_ : fluid_used_by_pairs_;
    // fluid values and chain-rule gradients with the weights folded in
    const double(&aj)[3][3] = mt.affine_value.jac;
    for (int f = 0; f < fwidth_; ++f) {
      if (!used[f]) continue;
      double* v = &fval_[static_cast<size_t>(f) * n];
      double* g[3] = {&fgrad_[(3 * static_cast<size_t>(f)) * n], &fgrad_[(3 * static_cast<size_t>(f) + 1) * n],
                      &fgrad_[(3 * static_cast<size_t>(f) + 2) * n]};
      for (int q = 0; q < n; ++q) {
        const double w = points_[q].weight;
        v[q] *= opt_.c2 * w;
        if (!gradients_ || listing_) continue;
        const double* jq = mt.affine ? &aj[0][0] : points_[q].jac.data();
        const double d0 = g[0][q], d1 = g[1][q], d2 = g[2][q];
        for (int b = 0; b < 3; ++b) g[b][q] = opt_.c1 * w * (d0 * jq[b] + d1 * jq[3 + b] + d2 * jq[6 + b]);
      }
    }
    for (size_t p = 0; p < pair_fluid_.size(); ++p) {
      if (twins && pair_source_[p] >= 0) continue;  // added with its source
      const std::vector<int>&fi = pair_fluid_[p], &si = pair_solid_[p];
      for (size_t a = 0; a < fi.size(); ++a) {
        const double* phi = &fval_[static_cast<size_t>(fi[a]) * n];
        const double* gphi = &fgrad_[3 * static_cast<size_t>(fi[a]) * n];
        double* col = pair_column(p, a);
        for (size_t b = 0; b < si.size(); ++b) {
          const double* psi = &sval_[static_cast<size_t>(si[b]) * n];
          const double* gpsi = &sgrad_[3 * static_cast<size_t>(si[b]) * n];
          double sum = 0;
          for (int q = 0; q < n; ++q) sum += psi[q] * phi[q];
          if (gradients_ && !listing_)
            for (int q = 0; q < n; ++q) sum += gpsi[q] * gphi[q] + gpsi[n + q] * gphi[n + q] + gpsi[2 * n + q] * gphi[2 * n + q];
          col[b] += sum;
          if (twins)
            for (int copy : pair_copies_[p]) pair_column(copy, a)[b] += sum;
        }
      }
    }
    if (listing_) add_listing(mt, n);
    return volume;
  }

  // The printed listings' reversed product, Grad(X,Y,Z) * Grad(u,v,w): pair index = vector component,
  //   sum_{a,b} d_b psi^(a) sum_c dX_a/ds_c d_b phi^(c).
  void add_listing(const MappedTet& mt, int n) {
    const double(&aj)[3][3] = mt.affine_value.jac;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        for (size_t ia = 0; ia < pair_fluid_[c].size(); ++ia) {
          const double* gphi = &fgrad_[3 * static_cast<size_t>(pair_fluid_[c][ia]) * n];
          // the column of pair c's ia-th fluid dof, from pair a's first multiplier dof on
          double* col = &block_[static_cast<size_t>(fcol_[frange_[c].first + static_cast<int>(ia)]) * ns_ + srange_[a].first];
          for (size_t ib = 0; ib < pair_solid_[a].size(); ++ib) {
            const double* gpsi = &sgrad_[3 * static_cast<size_t>(pair_solid_[a][ib]) * n];
            double sum = 0;
            for (int q = 0; q < n; ++q) {
              const double jac = mt.affine ? aj[a][c] : points_[q].jac[3 * a + c];
              sum += opt_.c1 * points_[q].weight * jac *
                     (gpsi[q] * gphi[q] + gpsi[n + q] * gphi[n + q] + gpsi[2 * n + q] * gphi[2 * n + q]);
            }
            col[ib] += sum;
          }
        }
  }

  // Both bases at the gathered points: fval_[f * n + q] and fgrad_[(3 f + i) * n + q] for the fitted
  // functions (likewise sval_, sgrad_); through the element's own evaluation where it is not polynomial.
  void evaluate_points(int kf, const MappedTet& mt, int n) {
    const size_t nn = static_cast<size_t>(n);
    eta_.resize(nn);
    xi_.resize(nn);
    for (int q = 0; q < n; ++q) {
      eta_[q] = points_[q].eta;
      xi_[q] = points_[q].xi;
    }
    fval_.resize(nn * fwidth_);
    fgrad_.resize(3 * nn * fwidth_);
    sval_.resize(nn * swidth_);
    sgrad_.resize(3 * nn * swidth_);
    evaluate_side(fpoly_, fluid_.space(), kf, eta_.data(), n, fval_.data(), fgrad_.data());
    evaluate_side(spoly_, solid_.space(), mt.k, xi_.data(), n, sval_.data(), sgrad_.data());
  }

  void evaluate_side(const PolynomialBasis3& poly, const Basis3& space, int k, const Point3* at, int n, double* value,
                     double* gradient) {
    if (poly.fitted()) {
      poly.evaluate_points(k, at, n, value, gradients_ ? gradient : nullptr);
      return;
    }
    const int nc = space.components();
    scratch_.resize(static_cast<size_t>(space.local_dofs()) * nc * 4);
    const std::vector<int>& functions = poly.functions();
    for (int q = 0; q < n; ++q) {
      space.evaluate(k, at[q], scratch_.data());
      for (size_t f = 0; f < functions.size(); ++f) {
        const double* o = &scratch_[functions[f] * 4];
        value[f * n + q] = o[0];
        for (int i = 0; i < 3; ++i) gradient[(3 * f + i) * n + q] = o[1 + i];
      }
    }
  }

  // Pair q repeats an earlier pair p when, function by function, both sides' functions are twins (or the
  // same): on elements of the shared fits its sums are p's, bit for bit (the components of vector spaces of
  // one element, as in the listings). Also which fluid functions any pair reads, and the computed pairs.
  void find_pair_twins() {
    const size_t np = pair_fluid_.size();
    pair_source_.assign(np, -1);
    pair_copies_.assign(np, {});
    auto rep = [](const PolynomialBasis3& poly, int f) { return poly.twin(f) >= 0 ? poly.twin(f) : f; };
    auto same = [&](const std::vector<int>& x, const std::vector<int>& y, const PolynomialBasis3& poly) {
      if (x.size() != y.size()) return false;
      for (size_t i = 0; i < x.size(); ++i)
        if (rep(poly, x[i]) != rep(poly, y[i])) return false;
      return true;
    };
    for (size_t q = 0; q < np; ++q)
      for (size_t p = 0; p < q && pair_source_[q] < 0; ++p)
        if (pair_source_[p] < 0 && same(pair_fluid_[p], pair_fluid_[q], fpoly_) && same(pair_solid_[p], pair_solid_[q], spoly_)) {
          pair_source_[q] = static_cast<int>(p);
          pair_copies_[p].push_back(static_cast<int>(q));
        }
    fluid_used_by_pairs_.assign(fwidth_, 0);
    fluid_used_by_sources_.assign(fwidth_, 0);
    for (size_t p = 0; p < np; ++p)
      for (int f : pair_fluid_[p]) {
        fluid_used_by_pairs_[f] = 1;
        if (pair_source_[p] < 0) fluid_used_by_sources_[f] = 1;
      }
  }

  // The block's entries of pair p's a-th fluid dof, from the pair's first multiplier dof on.
  double* pair_column(size_t p, size_t a) {
    return &block_[static_cast<size_t>(fcol_[frange_[p].first + static_cast<int>(a)]) * ns_ + srange_[p].first];
  }

  // Maps the used local dofs of fluid tetrahedron kf to columns of the block, adding new ones.
  void fluid_columns(int kf) {
    const int* fdofs = fluid_.dofs(kf);
    for (int j : fluid_used_) {
      const int g = fdofs[j];
      auto it = std::find(columns_.begin(), columns_.end(), g);
      if (it == columns_.end()) {
        columns_.push_back(g);
        const size_t used = (columns_.size() - 1) * ns_;  // the block grows by one zero column
        if (block_.size() < used + ns_) block_.resize(2 * (used + ns_));
        std::fill(block_.begin() + static_cast<long>(used), block_.begin() + static_cast<long>(used + ns_), 0.0);
        fcol_[j] = static_cast<int>(columns_.size()) - 1;
      } else {
        fcol_[j] = static_cast<int>(it - columns_.begin());
      }
    }
  }

  struct PointData {
    Point3 eta, xi;
    double weight;
    std::array<double, 9> jac;  // dX/ds where the map is not affine
  };
  static constexpr int kLinear = 64;  // at most this many fitted functions per side on the linear path

  const FluidSide3& fluid_;
  const SolidSide3& solid_;
  const SolidMap3& map_;
  const CouplingOptions& opt_;
  FluidSearch3 search_;
  const PolynomialBasis3 &fpoly_, &spoly_;
  int nf_, ns_, ncf_, ncs_;
  int fwidth_ = 0, swidth_ = 0;
  int hint_ = 0;
  bool gradients_ = false, listing_ = false, linear_ = false;
  std::vector<Range> frange_, srange_;
  std::vector<std::vector<int>> pair_fluid_, pair_solid_;  // per pair: fitted-function index of each local dof
  std::vector<int> pair_source_;               // per pair: the earlier pair it repeats, or -1
  std::vector<std::vector<int>> pair_copies_;  // per pair: the later pairs that repeat it
  std::vector<char> fluid_used_by_pairs_, fluid_used_by_sources_;  // per fitted fluid function
  std::vector<int> fluid_used_, solid_used_, sdofs_, fcol_, columns_;
  std::vector<double> block_;  // column-major, ns_ rows per column of columns_ (and spare)
  std::vector<PointData> points_;
  std::vector<Point3> eta_, xi_;
  std::vector<double> fval_, fgrad_, sval_, sgrad_, scratch_;
};

// The 2D contract (validation.hpp) with the 3D limits: rules up to degree 40, 8^subdivide parts per curved
// tetrahedron (at most 4096), no quadrature method.
void check_options(const Basis3& fluid_space, const Basis3& multiplier, const CouplingOptions& opt) {
  check_pairs_and_weights(fluid_space, multiplier, opt);
  if (opt.gradient == CouplingOptions::Gradient::Listing && opt.c1 != 0 && opt.fluid_components.size() != 3)
    throw Error("gradient=\"listing\" needs exactly three component pairs (a 3D vector field)");
  if (opt.qforder < -1 || opt.qforder > 40)
    throw Error("qforder=" + std::to_string(opt.qforder) +
                " out of range (0 to 40 in 3D, or -1 for the automatic choice: a rule of degree 40 has 9261 "
                "points per tetrahedron of a piece)");
  if (opt.subdivide < -1 || opt.subdivide > 4)
    throw Error("subdivide=" + std::to_string(opt.subdivide) +
                " out of range (0 to 4 in 3D, or -1 for the default: each curved solid tetrahedron is split "
                "into 8^subdivide parts, at most 4096)");
  if (opt.method != CouplingOptions::Method::Exact) throw Error("method=\"quadrature\" is 2D only; use \"exact\"");
  if (!(opt.outside_tol >= 0)) throw Error("outsidetol=" + option_value(opt.outside_tol) + " must be a number >= 0");
  if (opt.threads < 1) throw Error("threads=" + std::to_string(opt.threads) + " must be at least 1");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts)
    throw Error("part=[" + std::to_string(opt.part) + ", " + std::to_string(opt.parts) +
                "] needs 0 <= rank < size");
}

const Mesh3& checked(const Mesh3& mesh) {
  if (mesh.size() == 0) throw Error("empty fluid mesh");
  if (static_cast<int>(mesh.neighbours.size()) != mesh.size()) throw Error("fluid mesh adjacency not built");
  return mesh;
}

std::vector<int> share_in_order(const SolidSide3& solid, int first, int last) {
  if (first == 0 && last == solid.mesh().size()) return solid.order();
  std::vector<int> out;
  for (int k : solid.order())
    if (k >= first && k < last) out.push_back(k);
  return out;
}

}  // namespace

FluidSide3::FluidSide3(Mesh3 mesh, const Basis3& space, const std::vector<int>& components)
    : space_(space, morton_order(checked(mesh))), mesh_(renumbered(mesh, space_.original())), components_(components),
      degree_((check_components(space, components, "fluid", "fluid space"), polynomial_degree(space, components))),
      grid_(mesh_), basis_(space_, mesh_, degree_, components),
      dofs_(static_cast<size_t>(mesh_.size()) * space.local_dofs()) {
  for (int k = 0; k < mesh_.size(); ++k) space_.dofs(k, &dofs_[static_cast<size_t>(k) * space.local_dofs()]);
}

SolidSide3::SolidSide3(Mesh3 mesh, const Basis3& multiplier, const std::vector<int>& components)
    : mesh_(std::move(mesh)), space_(multiplier), components_(components),
      degree_((check_components(multiplier, components, "solid", "multiplier space"),
               polynomial_degree(multiplier, components))),
      basis_(multiplier, mesh_, degree_, components), order_(morton_order(mesh_)) {}

CsrMatrix assemble_coupling(const FluidSide3& fluid, const SolidSide3& solid, const SolidMap3& map,
                            const CouplingOptions& opt, CouplingReport3* report) {
  const auto start = std::chrono::steady_clock::now();
  check_options(fluid.space(), solid.space(), opt);
  if (opt.fluid_components != fluid.components()) throw Error("the fluid side was prepared for other components");
  if (opt.solid_components != solid.components()) throw Error("the solid side was prepared for other components");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts) throw Error("part must lie in [0, parts)");
  const int nt = solid.mesh().size();
  const int first = static_cast<int>(static_cast<long long>(nt) * opt.part / opt.parts);
  const int last = static_cast<int>(static_cast<long long>(nt) * (opt.part + 1) / opt.parts);

  CouplingReport3 total;
  total.fluid_degree = fluid.degree();
  total.solid_degree = solid.degree();
  // Exact for the product of the two bases (affine maps); 10 when an element is not polynomial.
  total.rule_degree = (total.fluid_degree < 0 || total.solid_degree < 0)
                          ? 10
                          : std::max(0, total.fluid_degree + total.solid_degree - (opt.c2 == 0 ? 2 : 0));
  // Threads only where no evaluation goes back to the caller's Basis or map (they need not be thread-safe).
  const bool parallel = fluid.basis().fitted() && solid.basis().fitted() && map.degree() >= 1;
  const int threads = parallel ? std::max(1, std::min(opt.threads, 64)) : 1;
  std::vector<Assembler3> workers;
  workers.reserve(threads);
  for (int t = 0; t < threads; ++t) workers.emplace_back(fluid, solid, map, opt, total);
  auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  total.setup_seconds = since();
  const std::vector<int> tets = share_in_order(solid, first, last);
  const int count = static_cast<int>(tets.size());
  auto share = [&](int t) { return tets.data() + static_cast<long long>(count) * t / threads; };
  if (threads == 1) {
    workers[0].run(tets.data(), tets.data() + count);
  } else {
    std::vector<std::thread> pool;
    std::vector<std::exception_ptr> errors(threads);
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        try {
          workers[t].run(share(t), share(t + 1));
        } catch (...) {
          errors[t] = std::current_exception();
        }
      });
    for (auto& th : pool) th.join();
    for (auto& e : errors)
      if (e) std::rethrow_exception(e);
  }
  total.pieces_seconds = since() - total.setup_seconds;
  std::vector<std::vector<Triplet>> parts;
  for (auto& w : workers) {
    const CouplingReport3& r = w.report;
    total.solid_tetrahedra += r.solid_tetrahedra;
    total.pieces += r.pieces;
    total.points += r.points;
    total.affine += r.affine;
    total.planar += r.planar;
    total.curved += r.curved;
    total.curved_rule_degree = std::max(total.curved_rule_degree, r.curved_rule_degree);
    total.image_volume += r.image_volume;
    total.outside_volume += r.outside_volume;
    if (r.worst_outside > total.worst_outside) {
      total.worst_outside = r.worst_outside;
      total.worst_tetrahedron = r.worst_tetrahedron;
    }
    parts.push_back(std::move(w.triplets));
  }
  if (!opt.drop_outside && total.outside_volume > opt.outside_tol * total.image_volume) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "the mapped solid leaves the fluid mesh: volume %.6g outside of %.6g (relative %.3g > %.3g); "
                  "worst is solid tetrahedron %d with %.6g outside. Pass outside=\"drop\" to drop that part.",
                  total.outside_volume, total.image_volume, total.outside_volume / total.image_volume, opt.outside_tol,
                  total.worst_tetrahedron, total.worst_outside);
    throw Error(msg);
  }
  CsrMatrix m = compress(solid.space().dof_count(), fluid.space().dof_count(), parts);
  total.seconds = since();
  if (report) *report = total;
  return m;
}

}  // namespace dlmfsi
