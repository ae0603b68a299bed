// The band where it crosses the faces of a solid tetrahedron T (PointIntegrator3::finish): T integrates the band
// inside itself, with its own polynomials, whatever its neighbours do.
//
// gather_band's columns run from a fluid face F's straight preimage (a = n . A - c = 0, A the sub-tetrahedron's
// affine interpolant) along the axis d to its true preimage (q = n . X - c = 0), carrying f_near - f_far (the two
// tetrahedra of F); they go on past T's faces so that their integrand stays smooth. So on each face sigma of T
// the columns that cross it must be taken back beyond it (those that start inside T) or added inside it (those
// that start outside and end inside). A column crosses sigma at xi exactly where a and q have opposite signs
// there, and its part from xi to q = 0 lies inside T where it runs into T: so the whole correction is
//   sum over sigma, F of  int_{xi in sigma, sign a(xi) != sign q(xi), start(xi) in F} |l(xi)| (d . nu) S(xi) dA,
// with S(xi) the column's mean of f_near - f_far from xi to its root l(xi) (add_column), nu sigma's unit normal
// into T: negative (an added band) where the column runs into T, positive (taken back) where it runs out. The
// condition start(xi) in F (the column's start xi - (a / rise) d, whose straight image lies in F's plane, lies in
// F) keeps each column with the face it starts from: coplanar faces share the plane's band between them, and a
// plane's extension beyond its face has no column.
//
// On each sub-face tau of sigma (a face of a sub-tetrahedron, where a is affine and q quadratic) the region is a
// polygon (tau less the walls of start() in F, and one side of a = 0) where q has one sign: conic_region_rule
// integrates it to the accuracy of Gauss-Legendre on smooth functions, with the conic q = 0 as the exact boundary.
// The faces F taken are those touching the fluid tetrahedra of the pieces on tau (faces_touching) whose plane
// comes within the band's reach of tau's image: a column's start lies within the band's thickness of its point.
#include <algorithm>
#include <cmath>

#include "fe/rules.hpp"
#include "geometry/predicates3d.hpp"
#include "integration/conic_region.hpp"
#include "integration/integrate_points3d.hpp"
#include "integration/reference_tet.hpp"
#include "mesh/face_star3d.hpp"
#include "sides/sides3d.hpp"

namespace dlmfsi {

void PointIntegrator3::start(const ClippedImage3& image) {
  terms_k_ = -1;
  side_faces_ = 0;
  for (int sub = 0; sub < 4; ++sub) {
    side_kf_[sub].clear();
    on_face_[sub] = -1;
  }
  if (!image.reference_side || !image.sub_xi) return;
  const Point3 ex[3] = {image.sub_xi[1] - image.sub_xi[0], image.sub_xi[2] - image.sub_xi[0],
                        image.sub_xi[3] - image.sub_xi[0]};
  for (int i = 0; i < 3; ++i) {
    straight_.ey[i] = image.sub_y[i + 1] - image.sub_y[0];
    straight_.cofactor[i] = cross(ex[(i + 1) % 3], ex[(i + 2) % 3]);
  }
  straight_.det = dot(ex[0], straight_.cofactor[0]);
  straight_.size2 = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      const Point3 d = image.sub_xi[b] - image.sub_xi[a];
      straight_.size2 = std::max(straight_.size2, dot(d, d));
    }
  const Point3 x0 = reference_position(image, Point3());
  straight_.whole_e[0] = reference_position(image, Point3{1, 0, 0}) - x0;
  straight_.whole_e[1] = reference_position(image, Point3{0, 1, 0}) - x0;
  straight_.whole_e[2] = reference_position(image, Point3{0, 0, 1}) - x0;
  const MappedTet& mt = image.tetrahedron;
  straight_.solid_det = volume6(mt.solid[0], mt.solid[1], mt.solid[2], mt.solid[3]);
  straight_.whole = true;
  for (int i = 0; i < 4 && straight_.whole; ++i) straight_.whole = barycentric(image.sub_xi[i], i) == 1;
  if (!fluid_) return;
  for (int sub = 0; sub < 4; ++sub) {  // the sub-tetrahedron's face opposite its corner sub lies on T's face i
    for (int i = 0; i < 4 && on_face_[sub] < 0; ++i) {
      bool all = true;
      for (int m = 0; m < 4 && all; ++m) all = m == sub || barycentric(image.sub_xi[m], i) == 0;
      if (all) on_face_[sub] = i;
    }
    side_faces_ += on_face_[sub] >= 0;
  }
}

void PointIntegrator3::note_side_piece(int kf, const Piece3& piece) {
  if (side_faces_ == 0) return;
  for (int f = 0; f < piece.faces; ++f) {
    unsigned common = 0xFu;
    for (int i = piece.face_start[f]; i < piece.face_start[f + 1]; ++i) common &= piece.planes[piece.face_index[i]];
    if (common == 0 || on_face_[__builtin_ctz(common)] < 0) continue;
    std::vector<int>& kfs = side_kf_[__builtin_ctz(common)];
    if (std::find(kfs.begin(), kfs.end(), kf) == kfs.end()) kfs.push_back(kf);
  }
}

void PointIntegrator3::finish(const ClippedImage3& image, LocalBlock& block) {
  if (side_faces_ == 0) return;
  const MappedTet& mt = image.tetrahedron;
  begin_across();
  point_jacobians_ = gradients_ && !weighted_sum_terms(mt);
  QuadraticTerms terms;
  terms.quadratic = mt.reference_hessian(terms.hessian);
  start_band_moments(image, terms);
  for (int sub = 0; sub < 4; ++sub)
    if (on_face_[sub] >= 0 && !side_kf_[sub].empty()) side_band(image, sub, terms);
  if (band_moments_) add_band_moments(image, block);
  if (groups_used_ > 0) add_across(mt, block);
}

const std::vector<PointIntegrator3::NearFace>& PointIntegrator3::near_faces(int kf) {
  constexpr int kSlots = 512;  // direct-mapped: neighbouring solid tetrahedra meet the same fluid tetrahedra
  if (near_.empty()) {
    near_.resize(kSlots);
    near_kf_.assign(kSlots, -1);
  }
  const int slot = kf % kSlots;
  std::vector<NearFace>& out = near_[slot];
  if (near_kf_[slot] == kf) return out;
  near_kf_[slot] = kf;
  out.clear();
  const Mesh3& mesh = fluid_->mesh();
  faces_touching(mesh, kf, touching_);
  for (const MeshFace3& f : touching_) {
    NearFace& nf = out.emplace_back();
    nf.face = f;
    Point3 c[4];
    mesh.corners(f.tet, c);
    for (int m = 0; m < 3; ++m) nf.v[m] = c[(f.face + 1 + m) & 3];
    nf.lo = {std::min({nf.v[0].x, nf.v[1].x, nf.v[2].x}), std::min({nf.v[0].y, nf.v[1].y, nf.v[2].y}),
             std::min({nf.v[0].z, nf.v[1].z, nf.v[2].z})};
    nf.hi = {std::max({nf.v[0].x, nf.v[1].x, nf.v[2].x}), std::max({nf.v[0].y, nf.v[1].y, nf.v[2].y}),
             std::max({nf.v[0].z, nf.v[1].z, nf.v[2].z})};
    nf.n = face_normal(f.tet, f.face);
  }
  return out;
}

// The sub-face: its corners (xi, and their images relative to the image's origin), a frame (o, e1, e2) of sigma,
// X there as a quadratic in (u, v) (exact for a quadratic map, interpolated at the corners and edge midpoints
// otherwise), and the band's reach.
void PointIntegrator3::side_face(const ClippedImage3& image, int sub, const QuadraticTerms& terms, SideFace& s) const {
  const int sigma = on_face_[sub];
  Point3 mid_x[6];  // X at the sub-tetrahedron's edge midpoints (edges (i, k), i < k, in order)
  for (int i = 0, m = 0; i < 4; ++i)
    for (int k = i + 1; k < 4; ++k, ++m) {
      const Point3 e = image.sub_xi[k] - image.sub_xi[i];
      if (terms.quadratic) {
        s.edge_hessians[m] = hessian_twice(terms.hessian, e);
      } else {  // e^T H e = 4 (X(a) + X(b) - 2 X(mid)) for a quadratic, twice that here for a margin
        mid_x[m] = reference_position(image, image.sub_xi[i] + 0.5 * e);
        s.edge_hessians[m] = 8.0 * ((image.sub_y[i] - image.origin) + (image.sub_y[k] - image.origin) - 2.0 * mid_x[m]);
      }
    }
  int corner[3];
  for (int m = 0; m < 3; ++m) {
    corner[m] = (sub + 1 + m) & 3;
    s.xi[m] = image.sub_xi[corner[m]];
    s.y[m] = image.sub_y[corner[m]] - image.origin;
  }
  const Point3 nu = barycentric_gradient(sigma);
  s.nu = (1 / std::sqrt(dot(nu, nu))) * nu;
  s.o = s.xi[0];
  s.e1 = (1 / std::sqrt(dot(s.xi[1] - s.xi[0], s.xi[1] - s.xi[0]))) * (s.xi[1] - s.xi[0]);
  s.e2 = cross(s.nu, s.e1);
  reference_value(image, s.o, s.x, s.d);
  if (terms.quadratic) {
    for (int i = 0; i < 3; ++i) {
      s.h_e1[i] = hessian_along(terms.hessian, i, s.e1);
      s.h_e2[i] = hessian_along(terms.hessian, i, s.e2);
    }
    s.x_u = s.e1.x * s.d[0] + s.e1.y * s.d[1] + s.e1.z * s.d[2];
    s.x_v = s.e2.x * s.d[0] + s.e2.y * s.d[1] + s.e2.z * s.d[2];
    s.x_uu = s.e1.x * s.h_e1[0] + s.e1.y * s.h_e1[1] + s.e1.z * s.h_e1[2];
    s.x_uv = s.e1.x * s.h_e2[0] + s.e1.y * s.h_e2[1] + s.e1.z * s.h_e2[2];
    s.x_vv = s.e2.x * s.h_e2[0] + s.e2.y * s.h_e2[1] + s.e2.z * s.h_e2[2];
  } else {
    // the quadratic through X at the corners p0 = (0, 0), p1 = (u1, 0), p2 = (u2, v2) and the edge midpoints:
    // along an edge of vector w, w^T H w = 4 (X(a) + X(b) - 2 X(mid)), and the slope from the end values
    auto mid = [&](int a, int b) {
      return mid_x[edge_index(std::min(corner[a], corner[b]), std::max(corner[a], corner[b]))];
    };
    const double u1 = dot(s.xi[1] - s.o, s.e1), u2 = dot(s.xi[2] - s.o, s.e1), v2 = dot(s.xi[2] - s.o, s.e2);
    const Point3 s01 = 4.0 * (s.y[0] + s.y[1] - 2.0 * mid(0, 1)), s02 = 4.0 * (s.y[0] + s.y[2] - 2.0 * mid(0, 2)),
                 s12 = 4.0 * (s.y[1] + s.y[2] - 2.0 * mid(1, 2));
    s.x_uu = (1 / (u1 * u1)) * s01;
    s.x_uv = (1 / (v2 * u1)) * (0.5 * (s02 - s12) - (u2 - 0.5 * u1) * u1 * s.x_uu);
    s.x_vv = (1 / (v2 * v2)) * (s02 - (u2 * u2) * s.x_uu - (2 * u2 * v2) * s.x_uv);
    s.x_u = (1 / u1) * (s.y[1] - s.y[0] - 0.5 * s01);
    s.x_v = (1 / v2) * (s.y[2] - s.y[0] - 0.5 * s02 - u2 * s.x_u);
  }
  // the box of the sub-face's image grown by the band's reach (X - A <= 3/16 max |e^T H e| per coordinate), four
  // times over: a column's start lies within the band's thickness of its point
  s.lo = s.y[0];
  s.hi = s.y[0];
  for (int m = 1; m < 3; ++m) {
    s.lo = {std::min(s.lo.x, s.y[m].x), std::min(s.lo.y, s.y[m].y), std::min(s.lo.z, s.y[m].z)};
    s.hi = {std::max(s.hi.x, s.y[m].x), std::max(s.hi.y, s.y[m].y), std::max(s.hi.z, s.y[m].z)};
  }
  double g = 0;
  for (const Point3& ehe : s.edge_hessians) g = std::max({g, std::fabs(ehe.x), std::fabs(ehe.y), std::fabs(ehe.z)});
  g = 4 * (3.0 / 16) * g + 1e-12 * std::sqrt(dot(s.hi - s.lo, s.hi - s.lo));
  s.lo = s.lo - Point3{g, g, g} + image.origin;
  s.hi = s.hi + Point3{g, g, g} + image.origin;
}

void PointIntegrator3::side_band(const ClippedImage3& image, int sub, const QuadraticTerms& terms) {
  SideFace s;
  side_face(image, sub, terms, s);
  // each face touching the fluid tetrahedra of the pieces on the sub-face once, where it comes near its image
  candidates_.clear();
  const size_t faces = 4 * static_cast<size_t>(fluid_->mesh().size());
  if (face_stamp_.size() != faces) face_stamp_.assign(faces, 0);
  if (++stamp_ == 0) {
    std::fill(face_stamp_.begin(), face_stamp_.end(), 0);
    stamp_ = 1;
  }
  for (int kf : side_kf_[sub])
    for (const NearFace& f : near_faces(kf)) {
      unsigned& mark = face_stamp_[4 * static_cast<size_t>(f.face.tet) + f.face.face];
      if (mark == stamp_) continue;
      mark = stamp_;
      if (f.hi.x < s.lo.x || f.lo.x > s.hi.x || f.hi.y < s.lo.y || f.lo.y > s.hi.y || f.hi.z < s.lo.z ||
          f.lo.z > s.hi.z)
        continue;
      candidates_.push_back(f);
    }
  for (const NearFace& f : candidates_) face_band(image, sub, terms, s, f);
}

namespace {

// A vertex of the sub-face's polygon as it is cut: xi, a = n . (A - y) and the barycentric coordinates in F of
// the straight image of the column's start.
struct CutVertex {
  Point3 xi;
  double value[4];
};

// The part of the polygon (in, n vertices) where side value[k] >= 0, into out; its size.
int keep_side(const CutVertex* in, int n, int k, double side, CutVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const CutVertex &p = in[i], &q = in[(i + 1) % n];
    const double vp = side * p.value[k], vq = side * q.value[k];
    if (vp >= 0) out[m++] = p;
    if ((vp >= 0) != (vq >= 0)) {
      const double t = vp / (vp - vq);
      CutVertex& c = out[m++];
      c.xi = p.xi + t * (q.xi - p.xi);
      for (int v = 0; v < 4; ++v) c.value[v] = p.value[v] + t * (q.value[v] - p.value[v]);
      c.value[k] = 0;
    }
  }
  return m;
}

}  // namespace

void PointIntegrator3::face_band(const ClippedImage3& image, int sub, const QuadraticTerms& terms, const SideFace& s,
                                 const NearFace& f) {
  Point3 n = f.n;
  const Point3 y = f.v[0] - image.origin;
  // |q - a| = |n . (X - A)| <= 3/16 max |n . e^T H e| on the sub-tetrahedron; twice that for the margin
  double reach = 0, a[3], size = 0;
  for (const Point3& ehe : s.edge_hessians) reach = std::max(reach, std::fabs(dot(n, ehe)));
  reach *= 2 * (3.0 / 16);
  for (int m = 0; m < 3; ++m) {
    a[m] = dot(n, s.y[m] - y);
    size = std::max(size, dot(s.y[m] - y, s.y[m] - y));
  }
  // Under a quadratic map q - a = n . (X - A) = -1/2 sum over the sub-face's edges ij of lambda_i lambda_j h_ij,
  // h_ij = n . e_ij^T H e_ij (X - A vanishes at its corners, and along an edge is -t (1 - t) e^T H e / 2): where
  // the three h have one sign, so has q - a all over the sub-face, and the side of a = 0 that needs the other
  // sign (a < 0 needs q > a, a > 0 needs q < a) has no band.
  // And since sum lambda_i lambda_j <= 1/3, q - a <= max(0, -h) / 6 and a - q <= max(0, h) / 6 there: the side
  // a < 0 has a band only where a > -max(0, -h) / 6, the side a > 0 only where a < max(0, h) / 6.
  const double lo = std::min({a[0], a[1], a[2]}), hi = std::max({a[0], a[1], a[2]});
  const double scale = std::sqrt(dot(n, n) * size);
  bool empty_side[2] = {false, false};  // a < 0, a > 0
  if (terms.quadratic) {
    double h_lo = 0, h_hi = 0;
    for (int m = 0; m < 3; ++m) {
      const int i = (sub + 1 + m) & 3, k = (sub + 1 + (m + 1) % 3) & 3;
      const double h = dot(n, s.edge_hessians[edge_index(std::min(i, k), std::max(i, k))]);
      h_lo = m == 0 ? h : std::min(h_lo, h);
      h_hi = m == 0 ? h : std::max(h_hi, h);
    }
    const double slack = 1e-12 * scale;
    empty_side[0] = h_lo >= 0 || hi < -(-h_lo / 6 * (1 + 1e-12) + slack);
    empty_side[1] = h_hi <= 0 || lo > h_hi / 6 * (1 + 1e-12) + slack;
    if (empty_side[0] && empty_side[1]) return;  // no band on the sub-face
  }
  if (hi < -(reach + 1e-12 * scale) || lo > reach + 1e-12 * scale) return;
  if (std::max(hi, -lo) <= 1e-10 * scale) {  // the sub-face's image in F's plane: no column crosses it
    bool in_plane = true;
    for (int m = 1; m < 4 && in_plane; ++m)
      in_plane = orient3d(f.v[0], f.v[1], f.v[2], image.sub_y[(sub + m) & 3]) == 0;
    if (in_plane) return;
  }
  BandFace face;
  double rise, height;
  if (!band_face(image, f.face.tet, f.face.face, f.face.across, terms, face, n, rise, height)) return;
  // a column from xi starts at xi - (a / rise) d, whose straight image is A(xi) - (a / rise) Y_d, Y_d = dA/dxi d
  const Point3 yd = straight_slope(face.d);
  const double yd_n = dot(n, yd);
  if (!(std::fabs(yd_n) > 0)) return;
  const Point3 fv[3] = {y, f.v[1] - image.origin, f.v[2] - image.origin};
  const Point3 normal = cross(fv[1] - fv[0], fv[2] - fv[0]);
  const double nn = dot(normal, normal);
  CutVertex poly[2][12];
  for (int m = 0; m < 3; ++m) {
    CutVertex& c = poly[0][m];
    c.xi = s.xi[m];
    c.value[0] = a[m];
    const Point3 start = s.y[m] - (a[m] / yd_n) * yd;
    for (int k = 0; k < 3; ++k)
      c.value[1 + k] = dot(cross(fv[(k + 2) % 3] - fv[(k + 1) % 3], start - fv[(k + 1) % 3]), normal) / nn;
  }
  int m = 3;
  for (int k = 1; k < 4 && m >= 3; ++k) {  // the walls: the start's barycentric coordinates in F >= 0
    m = keep_side(poly[0], m, k, 1, poly[1]);
    std::copy(poly[1], poly[1] + m, poly[0]);
  }
  if (m < 3) return;
  ColumnFrom column{face, n, y, rise, dot(face.d, s.nu), f.face.tet};
  if (band_moments_) face_moments_.clear();
  for (int side = -1; side <= 1; side += 2) {  // a < 0: the band where q > 0; a > 0: where q < 0
    if (empty_side[(side + 1) / 2]) continue;
    CutVertex part[12];
    const int kept = keep_side(poly[0], m, 0, side, part);
    if (kept < 3) continue;
    double uv[12][2];
    for (int i = 0; i < kept; ++i) {
      uv[i][0] = dot(part[i].xi - s.o, s.e1);
      uv[i][1] = dot(part[i].xi - s.o, s.e2);
    }
    band_region(image, terms, s, column, uv, kept, -side);
  }
  if (band_moments_) face_moments_.settle();
  if (band_moments_ && face_moments_.points() > 0) {  // f_K + in K, f_K' - in K' across
    add_face_moments(image, f.face.tet, 1);
    if (f.face.across >= 0) add_face_moments(image, f.face.across, -1);
  }
}

// The region's rules: degree 2 p + 4 for the outer integral (across the lines) and p + 2 along each line (the
// band's faces take 2 p + 2), two more on both on a sub-tetrahedron that is the whole solid tetrahedron (its band is
// thickest); on the tangent map of curved_per_tet3d.edp (the largest error over its tetrahedra alone at subdivide
// 0 / 1), 6.6e-14 / 1.6e-16, and 7.7e-12 at subdivide 0 with two less on the outer rule.
void PointIntegrator3::band_region(const ClippedImage3& image, const QuadraticTerms& terms, const SideFace& s,
                                   const ColumnFrom& c, const double (*uv)[2], int m, int sign) {
  const int extra = straight_.whole ? 2 : 0;
  const LineRule& outer = line_rule(2 * image.degree + 4 + extra);
  const LineRule& inner = line_rule(image.degree + 2 + extra);
  Quadratic2 q;  // n . (X - y) on sigma in (u, v)
  q.c0 = dot(c.n, s.x - c.y);
  q.cu = dot(c.n, s.x_u);
  q.cv = dot(c.n, s.x_v);
  q.cuu = 0.5 * dot(c.n, s.x_uu);
  q.cuv = dot(c.n, s.x_uv);
  q.cvv = 0.5 * dot(c.n, s.x_vv);
  region_points_.clear();
  conic_region_rule(uv, m, q, sign, outer, inner, image.degree, region_points_);
  if (region_points_.empty()) return;
  const Point3 d = c.face.d;
  const Point3 dd_o = d.x * s.d[0] + d.y * s.d[1] + d.z * s.d[2];
  const Point3 dd_u = s.e1.x * c.face.hd[0] + s.e1.y * c.face.hd[1] + s.e1.z * c.face.hd[2];
  const Point3 dd_v = s.e2.x * c.face.hd[0] + s.e2.y * c.face.hd[1] + s.e2.z * c.face.hd[2];
  for (const RegionPoint2& rp : region_points_) {
    const double u = rp.u, v = rp.v;
    const Point3 xi = s.o + (u * s.e1 + v * s.e2);
    Point3 x, D[3], dd;
    if (terms.quadratic) {  // X and dX/dxi by their Taylor terms about o
      x = s.x + (u * s.x_u + v * s.x_v) + ((0.5 * u * u) * s.x_uu + (u * v) * s.x_uv + (0.5 * v * v) * s.x_vv);
      if (point_jacobians_)
        for (int i = 0; i < 3; ++i) D[i] = s.d[i] + (u * s.h_e1[i] + v * s.h_e2[i]);
      dd = dd_o + (u * dd_u + v * dd_v);
    } else {
      reference_value(image, xi, x, D);
      dd = d.x * D[0] + d.y * D[1] + d.z * D[2];
    }
    const double root = column_root(image, c.face, c.n, c.y, xi, x, dd, c.rise);
    if (!std::isfinite(root) || root == 0) continue;
    const double column = rp.weight * std::fabs(root) * c.d_in * straight_.solid_det;
    if (band_moments_) {
      add_column_moments(c.face, xi, x, dd, root, column);
      continue;
    }
    add_column(image, -1, c.face, xi, x, dd, D, root, column, c.tet);
  }
}

}  // namespace dlmfsi
