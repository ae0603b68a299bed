#include "coupling.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "errors.hpp"
#include "fluid_search.hpp"
#include "polynomial_basis.hpp"
#include "predicates.hpp"
#include "rules.hpp"
#include "split.hpp"
#include "validation.hpp"

namespace dlmfsi {

std::string CouplingReport::summary() const {
  char s[512];
  std::snprintf(s, sizeof s,
                "dlmfsi: %ld solid triangles (%ld affine, %ld straight, %ld curved; %ld split into %ld parts), %ld pieces, "
                "%ld points, degrees fluid %d multiplier %d rule %d/%d, image area %.6g, outside %.3g, %.3f s "
                "(setup %.3f, pieces %.3f, matrix %.3f)",
                solid_triangles, affine, straight, curved, split, parts, pieces, points, fluid_degree,
                solid_degree, rule_degree,
                curved_rule_degree, image_area, outside_area, seconds, setup_seconds, pieces_seconds,
                seconds - setup_seconds - pieces_seconds);
  return s;
}

namespace {

struct Range {
  int first, last;
};

std::vector<int> unique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The local dofs that carry the listed components.
std::vector<int> used_dofs(const Basis& basis, const std::vector<int>& components) {
  std::vector<int> dofs;
  for (int c : components) {
    int first, last;
    basis.component_dofs(c, first, last);
    for (int d = first; d < last; ++d) dofs.push_back(d);
  }
  return unique(dofs);
}

// Everything one thread needs to assemble a run of solid triangles.
class Worker {
 public:
  Worker(const FluidSide& side, const Mesh& solid, const Basis& multiplier, const PolynomialBasis& solid_poly,
         const SolidMap& map, const CouplingOptions& opt, const CouplingReport& degrees)
      : side_(side), fluid_(side.mesh()), fluid_space_(side.space()), solid_(solid), multiplier_(multiplier),
        map_(map), opt_(opt), search_(side.grid()), nf_(side.space().local_dofs()), ns_(multiplier.local_dofs()),
        ncf_(side.space().components()), ncs_(multiplier.components()), fluid_poly_(side.basis()),
        solid_poly_(solid_poly) {
    report_.fluid_degree = degrees.fluid_degree;
    report_.solid_degree = degrees.solid_degree;
    report_.rule_degree = degrees.rule_degree;
    report_.curved_rule_degree = 0;
    const size_t np = opt.fluid_components.size();
    for (size_t p = 0; p < np; ++p) {
      Range f, s;
      fluid_space_.component_dofs(opt.fluid_components[p], f.first, f.last);
      multiplier.component_dofs(opt.solid_components[p], s.first, s.last);
      frange_.push_back(f);
      srange_.push_back(s);
    }
    fluid_used_ = used_dofs(fluid_space_, opt.fluid_components);
    solid_used_ = used_dofs(multiplier, opt.solid_components);
    fvals_.resize(static_cast<size_t>(nf_) * ncf_ * 3);
    svals_.resize(static_cast<size_t>(ns_) * ncs_ * 3);
    // The batch path: both bases fitted, the chain rule (or no gradient term).
    batch_ = fluid_poly_.fitted() && solid_poly_.fitted() &&
             (opt.gradient == CouplingOptions::Gradient::Chain || opt.c1 == 0);
    gradients_ = opt.c1 != 0;
    affine_rule_ = &triangle_rule(report_.rule_degree);
    if (batch_) {
      fwidth_ = static_cast<int>(fluid_poly_.functions().size());
      swidth_ = static_cast<int>(solid_poly_.functions().size());
      linear_ = fluid_poly_.degree() <= 1 && solid_poly_.degree() <= 1 && fwidth_ <= kLinearWidth &&
                swidth_ <= kLinearWidth;
      for (size_t p = 0; p < np; ++p) {
        pair_fluid_.push_back(index_in(fluid_poly_.functions(), opt.fluid_components[p], ncf_, frange_[p]));
        pair_solid_.push_back(index_in(solid_poly_.functions(), opt.solid_components[p], ncs_, srange_[p]));
      }
      find_pair_twins();
    }
    sdofs_.resize(ns_);
    fcol_.resize(nf_);
  }

  void run(const int* first, const int* last) {
    // about two fluid triangles' columns per solid triangle: room for most runs without regrowing
    triplets.reserve(static_cast<size_t>(last - first) * solid_used_.size() * 2 * fluid_used_.size());
    for (const int* k = first; k != last; ++k) solid_triangle(*k);
  }

  std::vector<Triplet> triplets;
  CouplingReport report_;

 private:
  void solid_triangle(int ks) {
    MappedTriangle mt;
    mt.prepare(solid_, map_, ks);
    multiplier_.dofs(ks, sdofs_.data());
    columns_.clear();
    ++report_.solid_triangles;
    (mt.affine ? report_.affine : (mt.straight ? report_.straight : report_.curved))++;
    const double image_area = 0.5 * area2(mt.image[0], mt.image[1], mt.image[2]);
    double outside = 0;
    const long pieces = report_.pieces;
    if (opt_.method == CouplingOptions::Method::Exact)
      outside = exact(mt);
    else
      outside = quadrature(mt);
    report_.image_area += image_area;
    // the image area less the pieces' areas: zero up to the round-off of the pieces' corners
    if (opt_.method == CouplingOptions::Method::Exact && outside > 0 && outside < mt.area_round_off(report_.pieces - pieces))
      outside = 0;
    outside = std::max(outside, 0.0);
    report_.outside_area += outside;
    if (outside > report_.worst_outside) {
      report_.worst_outside = outside;
      report_.worst_triangle = ks;
    }
    // Entries never touched stay exactly zero (a multiplier component paired with another fluid component).
    for (int i : solid_used_)
      for (size_t c = 0; c < columns_.size(); ++c)
        if (block_[c * ns_ + i] != 0.0) triplets.push_back({sdofs_[i], columns_[c], block_[c * ns_ + i]});
  }

  // The rule for triangle mt: exact for the product's degree p when the map is affine there; qforder when
  // given; -1 when the map is so far from affine (nonlinearity above kLeafNonlinearity) that its image is
  // split into parts first (split.hpp); otherwise rule_degree(nonlinearity).
  int rule_degree(const MappedTriangle& mt) {
    if (mt.affine) return report_.rule_degree;
    if (opt_.qforder >= 0) return opt_.qforder;
    if (mt.nonlinearity > kLeafNonlinearity) return -1;
    return rule_degree(mt.nonlinearity);
  }

  // Non-affine: the integrand in fluid coordinates is f(X^-1(y)) / det grad X, a series in the map's
  // nonlinearity d whose k-th term is a polynomial of degree about p + 2k, so degree p + 2k leaves about
  // (d / 3)^(k+1) (measured on single triangles with P1b bubbles and P2 maps, d = 0.009 to 0.3: the
  // relative error falls by about d / 3 for each 2 degrees, and below 1e-13 for the k chosen here: the
  // smallest with (d / 3)^(k+1) <= 1e-11).
  int rule_degree(double d) {
    d = std::min(std::max(d, 1e-300), kLeafNonlinearity);
    const int k = std::max(1, static_cast<int>(std::ceil(11.0 / -std::log10(d / 3))) - 1);
    const int degree = std::min(kMaxQforder, report_.rule_degree + 2 * k);
    report_.curved_rule_degree = std::max(report_.curved_rule_degree, degree);
    return degree;
  }

  // Quadrature method: on a leaf inside one fluid triangle the integrand c2 psi (phi o X) + c1 grad psi .
  // grad(phi o X), in the solid's reference coordinates, is a polynomial of degree p_solid + p_fluid * m for a
  // map of degree m, which this rule integrates exactly (qforder overrides).
  int quadrature_degree(const MappedTriangle& mt) {
    if (opt_.qforder >= 0) return opt_.qforder;
    if (mt.affine) return report_.rule_degree;
    const int m = map_.degree();
    if (m >= 1 && report_.fluid_degree >= 0 && report_.solid_degree >= 0) {
      const int degree = std::min(kMaxQforder, report_.solid_degree + report_.fluid_degree * m);
      report_.curved_rule_degree = std::max(report_.curved_rule_degree, degree);
      return degree;
    }
    return rule_degree(mt.nonlinearity);
  }

  // Clips the (straight) image, or its straight sub-triangles, against the fluid; returns the area outside.
  double exact(const MappedTriangle& mt) {
    double outside = 0;
    const int degree = rule_degree(mt);
    auto clip_image = [&](const Point img[3], int rule, const MapPart* frame) {
      const int o = orient2d(img[0], img[1], img[2]);
      if (o <= 0) throw Error("the map folds solid triangle " + std::to_string(mt.k) + " (a sub-triangle's image is " +
                              (o == 0 ? "flat)" : "clockwise)"));
      double covered = 0;
      search_.for_each_piece(img, hint_, [&](int kf, const Piece& piece) {
        covered += piece.area();
        integrate_piece(mt, kf, piece, rule, frame);
      });
      outside += 0.5 * area2(img[0], img[1], img[2]) - covered;
    };
    if (mt.straight && degree >= 0) {
      clip_image(mt.image, degree, nullptr);
      return outside;
    }
    // Curved edges (2^L x 2^L chords), or a map too far from affine for one rule (leaves until nearly
    // affine): straight parts, each with the pull-backs of its corners.
    const int level = mt.straight ? 0 : (opt_.subdivide >= 0 ? opt_.subdivide : 2);
    const double target = degree >= 0 ? std::numeric_limits<double>::infinity() : kLeafNonlinearity;
    if (!split_image(mt, level, target, kMaxLeafDepth, kMaxLeaves, parts_)) {
      char msg[240];
      std::snprintf(msg, sizeof msg,
                    "the map nearly folds solid triangle %d: its nonlinearity (%.3g on the triangle) stays above %.3g "
                    "on parts of 2^-%d of its size, or on more than %d parts",
                    mt.k, mt.nonlinearity, kLeafNonlinearity, kMaxLeafDepth, kMaxLeaves);
      throw Error(msg);
    }
    ++report_.split;
    report_.parts += static_cast<long>(parts_.size());
    // Each part gets the rule of its own nonlinearity (smaller than the triangle's), or qforder.
    for (const MapPart& part : parts_)
      clip_image(part.y, opt_.qforder >= 0 ? opt_.qforder : rule_degree(part.nonlinearity), &part);
    return outside;
  }

  // The positions, in the fitted functions' list, of component c's functions on local dofs [first, last).
  static std::vector<int> index_in(const std::vector<int>& functions, int c, int nc, Range dofs) {
    std::vector<int> out;
    for (int d = dofs.first; d < dofs.last; ++d)
      out.push_back(static_cast<int>(std::find(functions.begin(), functions.end(), d * nc + c) - functions.begin()));
    return out;
  }

  // The pull-backs of the piece's corners: affine, or Newton from the affine guess of the triangle or, in a
  // part of a split image (frame), of the part.
  void pull_back_corners(const MappedTriangle& mt, const Piece& piece, const MapPart* frame, Point* xi) const {
    MapValue mv;
    for (int v = 0; v < piece.n; ++v) {
      const Point y = piece.v[v];
      if (mt.affine)
        xi[v] = mt.affine_reference(y);
      else if (frame)
        xi[v] = mt.pull_back(y, from_reference(frame->xi, to_reference(frame->y, y)), mv);
      else
        xi[v] = mt.pull_back(y, mv);
    }
  }

  void integrate_piece(const MappedTriangle& mt, int kf, const Piece& piece, int degree, const MapPart* frame) {
    if (linear_ && mt.affine) {
      integrate_piece_linear(mt, kf, piece);
      return;
    }
    ++report_.pieces;
    fluid_columns(kf);
    Point xi[Piece::kMaxVertices];
    pull_back_corners(mt, piece, frame, xi);
    if (batch_)
      integrate_fan_batch(mt, kf, piece, xi, degree);
    else
      integrate_fan_points(mt, kf, piece, xi, degree);
  }

  // Point by point on the piece's fan, Newton started from the interpolation of the corners' pull-backs xi.
  void integrate_fan_points(const MappedTriangle& mt, int kf, const Piece& piece, const Point* xi_corners,
                            int degree) {
    const auto& rule = triangle_rule(degree);
    for (int t = 1; t + 1 < piece.n; ++t) {
      const Point tri[3] = {piece.v[0], piece.v[t], piece.v[t + 1]};
      const Point guess[3] = {xi_corners[0], xi_corners[t], xi_corners[t + 1]};
      const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
      for (const RulePoint& q : rule) {
        const Point y = from_reference(tri, q.xi);
        MapValue mv;
        const Point xi = mt.pull_back(y, from_reference(guess, q.xi), mv);
        const double det = mt.affine ? mt.affine_det : det2(mv.jac);
        if (!(det > 0)) throw Error("the map folds solid triangle " + std::to_string(mt.k));
        fluid_poly_.evaluate(kf, fluid_poly_.to_reference(kf, y), fvals_.data());
        solid_poly_.evaluate(mt.k, xi, svals_.data());
        accumulate(area * q.weight / det, mv.jac);
      }
    }
  }

  // Fitted bases: the rule's points on the piece's fan are gathered with their reference coordinates in
  // the fluid element (eta, affine in y: interpolated from the piece's corners) and in the solid element
  // (xi: interpolated too where the map is affine on the triangle; otherwise Newton's pull-back, started
  // from that interpolation between the corners' pull-backs); then each basis is evaluated on all points at
  // once and every entry of the block gets one weighted sum,
  //   block_ij += sum_q w_q [c2 psi_i phi_j + c1 grad psi_i . (grad phi_j dX/ds)],  w_q = area weight / det.
  void integrate_fan_batch(const MappedTriangle& mt, int kf, const Piece& piece, const Point* xi, int degree) {
    const auto& rule = mt.affine ? *affine_rule_ : triangle_rule(degree);
    Point eta[Piece::kMaxVertices];
    MapValue mv;
    for (int v = 0; v < piece.n; ++v) eta[v] = fluid_poly_.to_reference(kf, piece.v[v]);
    const size_t n = static_cast<size_t>(piece.n - 2) * rule.size();
    if (weight_.size() < n) {
      weight_.resize(n);
      peta_.resize(n);
      pxi_.resize(n);
      pjac_.resize(n);
      fbatch_.resize(3 * n * fwidth_);
      sbatch_.resize(3 * n * swidth_);
    }
    size_t q = 0;
    for (int t = 1; t + 1 < piece.n; ++t) {
      const Point tri[3] = {piece.v[0], piece.v[t], piece.v[t + 1]};
      const double area = 0.5 * area2(tri[0], tri[1], tri[2]);
      const Point et[3] = {eta[0], eta[t], eta[t + 1]}, xt[3] = {xi[0], xi[t], xi[t + 1]};
      for (const RulePoint& r : rule) {
        peta_[q] = from_reference(et, r.xi);
        pxi_[q] = from_reference(xt, r.xi);
        if (mt.affine) {
          weight_[q] = area * r.weight / mt.affine_det;
        } else {
          pxi_[q] = mt.pull_back(from_reference(tri, r.xi), pxi_[q], mv);
          const double det = det2(mv.jac);
          if (!(det > 0)) throw Error("the map folds solid triangle " + std::to_string(mt.k));
          weight_[q] = area * r.weight / det;
          pjac_[q] = {mv.jac[0][0], mv.jac[0][1], mv.jac[1][0], mv.jac[1][1]};
        }
        ++q;
      }
    }
    const int np = static_cast<int>(n);
    report_.points += np;
    double* fv = fbatch_.data();
    double* sv = sbatch_.data();
    const size_t fn = n * fwidth_, sn = n * swidth_;
    fluid_poly_.evaluate_points(kf, peta_.data(), np, fv, gradients_ ? fv + fn : nullptr, gradients_ ? fv + 2 * fn : nullptr);
    solid_poly_.evaluate_points(mt.k, pxi_.data(), np, sv, gradients_ ? sv + sn : nullptr, gradients_ ? sv + 2 * sn : nullptr);
    // Pairs that repeat an earlier pair's functions (on elements of the shared fits) copy its sums.
    const bool twins = fluid_poly_.shared(kf) && solid_poly_.shared(mt.k);
    const std::vector<char>& used = twins ? fluid_used_by_sources_ : fluid_used_by_pairs_;
    // Fluid values and chain-rule gradients with the weights folded in, per function along the points.
    const double c2 = opt_.c2;
    const double(&aj)[2][2] = mt.affine_value.jac;
    const std::array<double, 4> affine_jac{aj[0][0], aj[0][1], aj[1][0], aj[1][1]};
    for (size_t f = 0; f < static_cast<size_t>(fwidth_); ++f) {
      if (!used[f]) continue;
      double* v = fv + f * n;
      for (size_t k = 0; k < n; ++k) v[k] *= c2 * weight_[k];
      if (!gradients_) continue;
      double *gx = fv + fn + f * n, *gy = fv + 2 * fn + f * n;
      for (size_t k = 0; k < n; ++k) {
        // grad_s (phi o X)_b = sum_a d_a phi dX_a/ds_b, jac = (dX_0/ds_0, dX_0/ds_1, dX_1/ds_0, dX_1/ds_1)
        const std::array<double, 4>& jac = mt.affine ? affine_jac : pjac_[k];
        const double w = opt_.c1 * weight_[k];
        const double g0 = gx[k] * jac[0] + gy[k] * jac[2], g1 = gx[k] * jac[1] + gy[k] * jac[3];
        gx[k] = w * g0;
        gy[k] = w * g1;
      }
    }
    for (size_t p = 0; p < pair_fluid_.size(); ++p) {
      if (twins && pair_source_[p] >= 0) continue;  // added with its source
      const std::vector<int>&fi = pair_fluid_[p], &si = pair_solid_[p];
      for (size_t a = 0; a < fi.size(); ++a) {
        const double* phi = fv + static_cast<size_t>(fi[a]) * n;
        for (size_t b = 0; b < si.size(); ++b) {
          const double* psi = sv + static_cast<size_t>(si[b]) * n;
          double sum = 0;
          for (size_t k = 0; k < n; ++k) sum += psi[k] * phi[k];
          if (gradients_) {
            const double *px = psi + sn, *py = psi + 2 * sn, *gx = phi + fn, *gy = phi + 2 * fn;
            for (size_t k = 0; k < n; ++k) sum += px[k] * gx[k] + py[k] * gy[k];
          }
          pair_column(p, a)[b] += sum;
          if (twins)
            for (int copy : pair_copies_[p]) pair_column(copy, a)[b] += sum;
        }
      }
    }
  }

  // The block's entries of pair p's a-th fluid dof, from the pair's first multiplier dof on.
  double* pair_column(size_t p, size_t a) {
    return &block_[static_cast<size_t>(fcol_[frange_[p].first + static_cast<int>(a)]) * ns_ + srange_[p].first];
  }

  // Pair q repeats an earlier pair p when, function by function, both sides' functions are twins (or the same):
  // on elements of the shared fits its sums are p's, bit for bit. Also which fluid functions any pair reads,
  // and which the pairs that are computed read.
  void find_pair_twins() {
    const size_t np = pair_fluid_.size();
    pair_source_.assign(np, -1);
    pair_copies_.assign(np, {});
    auto rep = [](const PolynomialBasis& poly, int f) { return poly.twin(f) >= 0 ? poly.twin(f) : f; };
    auto same = [&](const std::vector<int>& x, const std::vector<int>& y, const PolynomialBasis& poly) {
      if (x.size() != y.size()) return false;
      for (size_t i = 0; i < x.size(); ++i)
        if (rep(poly, x[i]) != rep(poly, y[i])) return false;
      return true;
    };
    for (size_t q = 0; q < np; ++q)
      for (size_t p = 0; p < q && pair_source_[q] < 0; ++p)
        if (pair_source_[p] < 0 && same(pair_fluid_[p], pair_fluid_[q], fluid_poly_) &&
            same(pair_solid_[p], pair_solid_[q], solid_poly_)) {
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

  // Both bases of degree <= 1 and X affine on the triangle: on the piece P (area A, centroid c, central second
  // moments M = int_P (y - c)(y - c)^T dy) every product of two affine functions f g integrates exactly as
  //   int_P f g dy = A f(c) g(c) + grad f . M grad g,
  // and a product of gradients is constant. With y = X(s), ds = dy / det dX/ds and psi's gradient in y,
  // (dX/ds)^-T grad_s psi, the block gets
  //   (c2 / det) [A phi_j(c) psi_i(c) + grad phi_j . M grad_y psi_i] + c1 (A / det) grad_s psi_i . (grad phi_j dX/ds).
  void integrate_piece_linear(const MappedTriangle& mt, int kf, const Piece& piece) {
    ++report_.pieces;
    fluid_columns(kf);
    // area, centroid and second moments from the fan, in coordinates relative to the first corner
    const Point o = piece.v[0];
    double area = 0, cx = 0, cy = 0, mxx = 0, mxy = 0, myy = 0;
    for (int t = 1; t + 1 < piece.n; ++t) {
      const Point p = piece.v[t] - o, q = piece.v[t + 1] - o;
      const double a = 0.5 * cross(p, q);  // the triangle (0, p, q): int x x^T = a/6 (p p^T + q q^T + (p q^T + q p^T)/2)
      area += a;
      cx += a * (p.x + q.x) / 3;
      cy += a * (p.y + q.y) / 3;
      mxx += a / 6 * (p.x * p.x + q.x * q.x + p.x * q.x);
      myy += a / 6 * (p.y * p.y + q.y * q.y + p.y * q.y);
      mxy += a / 12 * (2 * p.x * p.y + 2 * q.x * q.y + p.x * q.y + q.x * p.y);
    }
    report_.points += 1;
    if (!(area > 0)) return;  // a piece of round-off size: nothing to add
    cx /= area;
    cy /= area;
    mxx -= area * cx * cx;  // about the centroid
    myy -= area * cy * cy;
    mxy -= area * cx * cy;
    const Point c{o.x + cx, o.y + cy};
    const Point eta = fluid_poly_.to_reference(kf, c), xi = mt.affine_reference(c);
    double fv[kLinearWidth], fgx[kLinearWidth], fgy[kLinearWidth], sv[kLinearWidth], sgx[kLinearWidth], sgy[kLinearWidth];
    fluid_poly_.evaluate_affine(kf, eta, fv, fgx, fgy);
    solid_poly_.evaluate_affine(mt.k, xi, sv, sgx, sgy);
    const double(&j)[2][2] = mt.affine_value.jac;  // dX_a/ds_b
    const double det = mt.affine_det, mass = opt_.c2 / det, stiff = opt_.c1 * area / det;
    // per fluid function: c2/det (A phi(c), M grad phi), and the chain-rule gradient times c1 A / det
    double fa[kLinearWidth], fmx[kLinearWidth], fmy[kLinearWidth], fcx[kLinearWidth], fcy[kLinearWidth];
    for (int f = 0; f < fwidth_; ++f) {
      fa[f] = mass * area * fv[f];
      fmx[f] = mass * (mxx * fgx[f] + mxy * fgy[f]);
      fmy[f] = mass * (mxy * fgx[f] + myy * fgy[f]);
      fcx[f] = stiff * (fgx[f] * j[0][0] + fgy[f] * j[1][0]);
      fcy[f] = stiff * (fgx[f] * j[0][1] + fgy[f] * j[1][1]);
    }
    // per solid function: its gradient in y, (dX/ds)^-T grad_s psi
    double syx[kLinearWidth], syy[kLinearWidth];
    for (int f = 0; f < swidth_; ++f) {
      syx[f] = (j[1][1] * sgx[f] - j[1][0] * sgy[f]) / det;
      syy[f] = (j[0][0] * sgy[f] - j[0][1] * sgx[f]) / det;
    }
    for (size_t p = 0; p < pair_fluid_.size(); ++p) {
      const std::vector<int>&fi = pair_fluid_[p], &si = pair_solid_[p];
      for (size_t a = 0; a < fi.size(); ++a) {
        const int f = fi[a];
        double* col = pair_column(p, a);
        for (size_t b = 0; b < si.size(); ++b) {
          const int g = si[b];
          double sum = fa[f] * sv[g] + fmx[f] * syx[g] + fmy[f] * syy[g];
          if (gradients_) sum += fcx[f] * sgx[g] + fcy[f] * sgy[g];
          col[b] += sum;
        }
      }
    }
  }

  // Composite rule on sub-triangles of the reference triangle; returns the (fluid-space) area outside.
  double quadrature(const MappedTriangle& mt) {
    struct Sub {
      Point ref[3], img[3];
      int depth;
    };
    const int max_depth =
        std::min(12, std::max(0, static_cast<int>(std::ceil(std::log(1 / std::max(opt_.tol, 1e-300)) / std::log(4.0)))));
    const double solid_jacobian = area2(mt.solid[0], mt.solid[1], mt.solid[2]);  // ds = this * dxi
    const auto& rule = triangle_rule(quadrature_degree(mt));
    double outside = 0;
    std::vector<Sub> stack{{{{0, 0}, {1, 0}, {0, 1}}, {mt.image[0], mt.image[1], mt.image[2]}, 0}};
    auto image_of = [&](Point xi) { return mt.affine ? from_reference(mt.image, xi) : mt.at(xi).x; };
    while (!stack.empty()) {
      Sub s = stack.back();
      stack.pop_back();
      if (s.depth < max_depth && !one_fluid_triangle(s.img)) {
        const Point m[3] = {0.5 * (s.ref[0] + s.ref[1]), 0.5 * (s.ref[1] + s.ref[2]), 0.5 * (s.ref[2] + s.ref[0])};
        const Point mi[3] = {image_of(m[0]), image_of(m[1]), image_of(m[2])};
        stack.push_back({{s.ref[0], m[0], m[2]}, {s.img[0], mi[0], mi[2]}, s.depth + 1});
        stack.push_back({{m[0], s.ref[1], m[1]}, {mi[0], s.img[1], mi[1]}, s.depth + 1});
        stack.push_back({{m[2], m[1], s.ref[2]}, {mi[2], mi[1], s.img[2]}, s.depth + 1});
        stack.push_back({{m[1], m[2], m[0]}, {mi[1], mi[2], mi[0]}, s.depth + 1});
        continue;
      }
      ++report_.pieces;
      const double ref_area = 0.5 * area2(s.ref[0], s.ref[1], s.ref[2]);
      for (const RulePoint& q : rule) {
        const Point xi = from_reference(s.ref, q.xi);
        MapValue mv = mt.affine ? mt.affine_value : mt.at(xi);
        if (mt.affine) mv.x = from_reference(mt.image, xi);
        const double ds = q.weight * ref_area * solid_jacobian;
        const int kf = search_.locate(mv.x, hint_);
        if (kf < 0) {
          outside += ds * std::fabs(det2(mv.jac));
          continue;
        }
        hint_ = kf;
        fluid_columns(kf);
        fluid_poly_.evaluate(kf, fluid_poly_.to_reference(kf, mv.x), fvals_.data());
        solid_poly_.evaluate(mt.k, xi, svals_.data());
        accumulate(ds, mv.jac);
      }
    }
    return outside;
  }

  // Do the three points lie in one closed fluid triangle?
  bool one_fluid_triangle(const Point img[3]) {
    const int k = search_.locate(img[0], hint_);
    if (k < 0) return false;
    hint_ = k;
    for (int i = 1; i < 3; ++i)
      for (int e = 0; e < 3; ++e)
        if (orient2d(fluid_.vertex(k, e), fluid_.vertex(k, (e + 1) % 3), img[i]) < 0) return false;
    return true;
  }

  // Maps the used local dofs of fluid triangle kf to columns of the block, adding new ones.
  void fluid_columns(int kf) {
    const int* fdofs = side_.dofs(kf);
    for (int j : fluid_used_) {
      const int g = fdofs[j];
      auto it = std::find(columns_.begin(), columns_.end(), g);
      if (it == columns_.end()) {
        columns_.push_back(g);
        const size_t used = (columns_.size() - 1) * ns_;  // the block grows by one zero column
        if (block_.size() < used + ns_) block_.resize(2 * (used + ns_));
        std::fill(block_.begin() + used, block_.begin() + used + ns_, 0.0);
        fcol_[j] = static_cast<int>(columns_.size()) - 1;
      } else {
        fcol_[j] = static_cast<int>(it - columns_.begin());
      }
    }
  }

  // block += ds * [c2 psi_i . phi_j + c1 grad psi_i : grad(phi_j o X)] at one point; fvals_, svals_ filled.
  void accumulate(double ds, const double jac[2][2]) {
    ++report_.points;
    auto f = [&](int j, int c) { return &fvals_[(static_cast<size_t>(j) * ncf_ + c) * 3]; };
    auto s = [&](int i, int c) { return &svals_[(static_cast<size_t>(i) * ncs_ + c) * 3]; };
    const double c1 = opt_.c1 * ds, c2 = opt_.c2 * ds;
    const bool chain = opt_.gradient == CouplingOptions::Gradient::Chain;
    for (size_t p = 0; p < frange_.size(); ++p) {
      const int fc = opt_.fluid_components[p], sc = opt_.solid_components[p];
      for (int j = frange_[p].first; j < frange_[p].last; ++j) {
        const double* phi = f(j, fc);
        // grad_s (phi o X)_b = sum_a d_a phi * dX_a/ds_b
        const double g0 = phi[1] * jac[0][0] + phi[2] * jac[1][0];
        const double g1 = phi[1] * jac[0][1] + phi[2] * jac[1][1];
        double* col = &block_[static_cast<size_t>(fcol_[j]) * ns_];
        for (int i = srange_[p].first; i < srange_[p].last; ++i) {
          const double* psi = s(i, sc);
          double v = c2 * psi[0] * phi[0];
          if (chain) v += c1 * (psi[1] * g0 + psi[2] * g1);
          col[i] += v;
        }
      }
    }
    if (chain || opt_.c1 == 0) return;
    // Listing: sum_{a,b} d_b psi^{s_a} sum_c dX_a/ds_c d_b phi^{f_c} (pair index = vector component).
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const double w = c1 * jac[a][c];
        const int sc = opt_.solid_components[a], fc = opt_.fluid_components[c];
        for (int j = frange_[c].first; j < frange_[c].last; ++j) {
          const double* phi = f(j, fc);
          double* col = &block_[static_cast<size_t>(fcol_[j]) * ns_];
          for (int i = srange_[a].first; i < srange_[a].last; ++i) {
            const double* psi = s(i, sc);
            col[i] += w * (psi[1] * phi[1] + psi[2] * phi[2]);
          }
        }
      }
  }

  const FluidSide& side_;
  const Mesh& fluid_;
  const Basis& fluid_space_;
  const Mesh& solid_;
  const Basis& multiplier_;
  const SolidMap& map_;
  const CouplingOptions& opt_;
  FluidSearch search_;
  int nf_, ns_, ncf_, ncs_;
  const PolynomialBasis &fluid_poly_, &solid_poly_;
  int hint_ = 0;
  std::vector<Range> frange_, srange_;
  std::vector<int> fluid_used_, solid_used_;
  std::vector<double> fvals_, svals_, block_;  // block_: column-major, ns_ rows per column of columns_ (and spare)
  std::vector<int> sdofs_, fcol_, columns_;
  // batch path
  bool batch_ = false, gradients_ = false;
  // linear path (both bases of degree <= 1, affine triangles): at most this many fitted functions per side
  static constexpr int kLinearWidth = 48;
  bool linear_ = false;
  const std::vector<RulePoint>* affine_rule_ = nullptr;  // exact for the product of the bases
  // Images of triangles whose nonlinearity is above this are split into parts (split.hpp) on which it is
  // at most this: a rule of degree p + 20 there (rule_degree(double)).
  static constexpr double kLeafNonlinearity = 0.25;
  static constexpr int kMaxLeafDepth = 30, kMaxLeaves = 100000;
  std::vector<MapPart> parts_;
  int fwidth_ = 0, swidth_ = 0;
  std::vector<std::vector<int>> pair_fluid_, pair_solid_;  // per pair: fitted-function index of each local dof
  std::vector<int> pair_source_;                  // per pair: the earlier pair it repeats, or -1
  std::vector<std::vector<int>> pair_copies_;     // per pair: the later pairs that repeat it
  std::vector<char> fluid_used_by_pairs_, fluid_used_by_sources_;  // per fitted fluid function
  std::vector<double> weight_, fbatch_, sbatch_;
  std::vector<Point> peta_, pxi_;
  std::vector<std::array<double, 4>> pjac_;
};

// The solid triangles of share [first, last) of the indices, in the solid side's order.
std::vector<int> share_in_order(const SolidSide& solid, int first, int last) {
  if (first == 0 && last == solid.mesh().size()) return solid.order();
  std::vector<int> out;
  out.reserve(last - first);
  for (int k : solid.order())
    if (k >= first && k < last) out.push_back(k);
  return out;
}

}  // namespace

CsrMatrix assemble_coupling(const Mesh& fluid, const Basis& fluid_space, const Mesh& solid, const Basis& multiplier,
                            const SolidMap& map, const CouplingOptions& opt, CouplingReport* report) {
  check_options(fluid_space, multiplier, opt);
  const FluidSide side(fluid, fluid_space, opt.fluid_components);
  return assemble_coupling(side, solid, multiplier, map, opt, report);
}

CsrMatrix assemble_coupling(const FluidSide& side, const Mesh& solid, const Basis& multiplier, const SolidMap& map,
                            const CouplingOptions& opt, CouplingReport* report) {
  check_options(side.space(), multiplier, opt);
  const auto start = std::chrono::steady_clock::now();
  const SolidSide solid_side(solid, multiplier, opt.solid_components);
  const double prepare = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CsrMatrix m = assemble_coupling(side, solid_side, map, opt, report);
  if (report) {  // the solid side's fit belongs to this call's setup
    report->setup_seconds += prepare;
    report->seconds += prepare;
  }
  return m;
}

CsrMatrix assemble_coupling(const FluidSide& side, const SolidSide& solid_side, const SolidMap& map,
                            const CouplingOptions& opt, CouplingReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const Basis& fluid_space = side.space();
  const Basis& multiplier = solid_side.space();
  const Mesh& solid = solid_side.mesh();
  check_options(fluid_space, multiplier, opt);
  if (opt.fluid_components != side.components()) throw Error("the fluid side was prepared for other components");
  if (opt.solid_components != solid_side.components()) throw Error("the solid side was prepared for other components");
  const int first = static_cast<int>(static_cast<long long>(solid.size()) * opt.part / opt.parts);
  const int last = static_cast<int>(static_cast<long long>(solid.size()) * (opt.part + 1) / opt.parts);

  CouplingReport total;
  total.fluid_degree = side.degree();
  total.solid_degree = solid_side.degree();
  // Exact for the product of the two bases (affine maps); 10 when an element is not polynomial.
  const int product = (total.fluid_degree < 0 || total.solid_degree < 0)
                          ? 10
                          : std::max(0, total.fluid_degree + total.solid_degree - (opt.c2 == 0 ? 2 : 0));
  total.rule_degree = product;
  if (opt.method == CouplingOptions::Method::Quadrature && opt.qforder >= 0) total.rule_degree = opt.qforder;

  const PolynomialBasis& fluid_poly = side.basis();
  const PolynomialBasis& solid_poly = solid_side.basis();
  // Threads only where no evaluation goes back to the caller's Basis or map (they need not be thread-safe).
  const bool parallel = fluid_poly.fitted() && solid_poly.fitted() && map.degree() >= 1;
  const int threads = parallel ? std::max(1, std::min(opt.threads, 64)) : 1;
  // The map into the fluid side's scaled coordinates.
  const ScaledMap scaled_map(map, side.scale());
  const SolidMap& fluid_map = side.scale() == 0 ? map : scaled_map;
  std::vector<Worker> workers;
  workers.reserve(threads);
  for (int t = 0; t < threads; ++t)
    workers.emplace_back(side, solid, multiplier, solid_poly, fluid_map, opt, total);
  auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  total.setup_seconds = since();
  // Contiguous shares of the ordered triangles, so that the sums come out in the same order for any thread
  // count.
  const std::vector<int> triangles = share_in_order(solid_side, first, last);
  const int count = static_cast<int>(triangles.size());
  auto share = [&](int t) { return triangles.data() + static_cast<long long>(count) * t / threads; };
  if (threads == 1) {
    workers[0].run(triangles.data(), triangles.data() + count);
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
    const CouplingReport& r = w.report_;
    total.solid_triangles += r.solid_triangles;
    total.pieces += r.pieces;
    total.points += r.points;
    total.split += r.split;
    total.parts += r.parts;
    total.affine += r.affine;
    total.straight += r.straight;
    total.curved += r.curved;
    total.curved_rule_degree = std::max(total.curved_rule_degree, r.curved_rule_degree);
    total.image_area += r.image_area;
    total.outside_area += r.outside_area;
    if (r.worst_outside > total.worst_outside) {
      total.worst_outside = r.worst_outside;
      total.worst_triangle = r.worst_triangle;
    }
    parts.push_back(std::move(w.triplets));
  }
  // Compared in the scaled coordinates, reported in the caller's units.
  const bool leaves = total.outside_area > opt.outside_tol * total.image_area;
  const double relative = total.outside_area / total.image_area;
  const double area_unit = std::ldexp(1.0, 2 * side.scale());
  total.image_area *= area_unit;
  total.outside_area *= area_unit;
  total.worst_outside *= area_unit;
  if (!opt.drop_outside && leaves) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "the mapped solid leaves the fluid mesh: area %.6g outside of %.6g (relative %.3g > %.3g); "
                  "worst is solid triangle %d with %.6g outside. Pass outside=\"drop\" to drop that part.",
                  total.outside_area, total.image_area, relative, opt.outside_tol,
                  total.worst_triangle, total.worst_outside);
    throw Error(msg);
  }
  CsrMatrix m = compress(multiplier.dof_count(), fluid_space.dof_count(), parts);
  check_finite(m, opt);
  total.seconds = since();
  if (report) *report = total;
  return m;
}

}  // namespace dlmfsi
