// The point-by-point piece integrator for tetrahedra: any basis (fitted, or evaluated through the element
// itself) and either gradient product. A rule on each tetrahedron of the piece: the points with their
// reference coordinates in the fluid element (eta, affine in y) and in the solid element (xi: the affine
// pull-back, or Newton's from the interpolation of the piece's corners' pull-backs), both bases evaluated
// on all points at once (point_values3d.hpp), then
//   block_ij += sum_q w_q [c2 psi_i phi_j + c1 grad_s psi_i . (J^T grad phi_j)],  w_q = volume weight / det J,
// or with the listings' reversed product (three pairs, the pair index being the vector component)
//   grad psi : G = sum_{a,b} d_b psi^(a) sum_c dX_a/ds_c d_b phi^(c).
// On elements of the shared fits, a pair that repeats an earlier pair's functions (ComponentPairs) copies
// its sums. Under a quadratic map with a multiplier of degree <= 2 the same sums are regrouped as weighted sums
// of the fluid's values and gradients (weighted_sum_terms), and neither basis is evaluated point by point.
#pragma once
#include <array>
#include <vector>

#include "integration/integrator3d.hpp"
#include "integration/point_values3d.hpp"
#include "integration/conic_region.hpp"
#include "integration/point_moments3d.hpp"
#include "mesh/face_star3d.hpp"

namespace dlmfsi {

struct LineRule;

class FluidSide3;

class PointIntegrator3 : public PieceIntegrator3 {
 public:
  // fluid: its mesh's adjacency and dofs, for the band on the reference side where a sub-tetrahedron's face lies
  // in a fluid face plane (gather_band); without it such faces are taken as faces inside the sub-tetrahedron.
  PointIntegrator3(const Integrand3& integrand, CouplingReport& counts, const FluidSide3* fluid = nullptr);
  // start: on the reference side, the sub-tetrahedron's straight image and its faces on the solid tetrahedron's;
  // finish: the band where it crosses them, once the image's pieces are done (side_band3d.cpp).
  void start(const ClippedImage3& image) override;
  double integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) override;
  void finish(const ClippedImage3& image, LocalBlock& block) override;

  // A point of the solid tetrahedron whose image lies in fluid tetrahedron kf: reference coordinates in kf
  // (eta) and in the solid tetrahedron (xi), its weight in solid measure (ds; a piece's points carry
  // dy / det dX/ds, the same), and dX/ds there where the map is not affine.
  struct PointData {
    Point3 eta, xi;
    double weight;
    std::array<double, 9> jac;
  };
  // Adds sum_q weight_q f_ij(point q) over points all in fluid tetrahedron kf (entered in the block by the
  // caller): the quadrature method's way in (quadrature_method3d.hpp).
  void add_points(const MappedTet& mt, int kf, const PointData* points, int n, LocalBlock& block);

 private:
  // Evaluates both bases on the gathered points (in kf) and adds the sums to the block.
  void add_gathered(const MappedTet& mt, int kf, LocalBlock& block);
  // The rule's points on the piece's tetrahedra, into eta_, xi_, weight_ (and jac_); returns the piece's volume.
  double gather(const ClippedImage3& image, int kf, const Piece3& piece);
  // The same on the reference side (image.reference_side): the rule on the preimages of the piece's tetrahedra
  // under the sub-tetrahedron's affine interpolant, the fluid evaluated at the map's value at each point; and
  // the band between each of the piece's faces on a fluid face plane and that plane's true preimage, in
  // columns along one solid axis (Gauss-Legendre points along each column: gather_band).
  double gather_reference_side(const ClippedImage3& image, int kf, const Piece3& piece);
  // A quadratic map's terms for one piece's points (gather_reference_side forms them once for the volume and the
  // band): its constant hessian, and where the points take X alone (dX/dxi not read), dX/dxi at xi = 0, from which
  // X follows by Taylor terms.
  struct QuadraticTerms {
    bool quadratic = false, alone = false;
    double hessian[3][3][3];
    Point3 d_corner[3];
  };
  // The band's points (gather_reference_side): columns from the piece's faces on fluid face planes to the
  // planes' true preimages; xi_corner the piece's corners taken back, solid_det 6 |solid tetrahedron|.
  void gather_band(const ClippedImage3& image, int kf, const Piece3& piece, const Point3* xi_corner,
                   double solid_det, const QuadraticTerms& terms);
  // A band face's columns: the axis d (in xi), a quadratic map's H d (dX/dxi's slope along d) and d^T H d, with
  // the latter in the reference coordinates of kf and of the fluid tetrahedron across (-1: none).
  struct BandFace {
    Point3 d, hd[3], dhd, eta_dhd, across_dhd;
    bool quadratic = false;
    int across = -1;
  };
  // The columns of kf's face plane j (its fluid neighbour across): face, the plane's outward normal n (n . y grows
  // out of kf), rise = d(n . A)/dl along the axis and height = d . nu; false where the plane's preimage under the
  // sub-tetrahedron's straight image has no gradient.
  bool band_face(const ClippedImage3& image, int kf, int j, int across, const QuadraticTerms& terms, BandFace& face,
                 Point3& n, double& rise, double& height) const;
  // The normal of kf's face j, outward (n . y grows out of kf), scaled so that n . (y - y_j) = -lambda_j(y).
  Point3 face_normal(int kf, int j) const;
  // A column's length from xi (X = x there, dX/dl = dd along face.d): the root nearest 0 of n . (X(xi + l d) - y)
  // (y a point of the plane), exact for a quadratic map; rise = d(n . A)/dl, the straight image's slope.
  double column_root(const ClippedImage3& image, const BandFace& face, Point3 n, Point3 y, Point3 xi, Point3 x,
                     Point3 dd, double rise) const;
  // The points of one column (gather_band): from xi, where X is x0, dX/dl is dd and dX/dxi is D (where the
  // points carry it), to l, the column's weight int_face's l height dA; in kf, and with the opposite weight in
  // the fluid tetrahedron across (across_).
  // near >= 0: the column's own fluid tetrahedron (face's kf), other than the piece's kf: its points go with those
  // of the tetrahedra across (kf -1: no piece).
  void add_column(const ClippedImage3& image, int kf, const BandFace& face, Point3 xi, Point3 x0, Point3 dd,
                  const Point3 (&D)[3], double l, double column, int near = -1);
  // The band near the piece face f's edges on fluid edges (edge_strip3d.cpp; with the fluid side, whose mesh tells
  // the face beyond an edge): where the column's start and the point at which the segment from A to X crosses the
  // face plane j lie on opposite sides of an edge, each edge's strip of columns taken back or added from there on.
  void edge_strips(const ClippedImage3& image, int kf, int j, const Piece3& piece, int f, const Point3* xi_corner,
                   double solid_det, const BandFace& face, Point3 n, double rise, double height);
  // One edge's strip: the edge between kf's face plane and its face g_face, y_edge a point of it, the piece's
  // face along it from xi_a to xi_b (xi_in a point of the face off the edge), the strip's direction across the
  // edge at each end (0: across it in the start plane).
  void edge_strip(const ClippedImage3& image, int kf, int j, int g_face, Point3 y_edge, Point3 xi_a, Point3 xi_b,
                  Point3 xi_in, const Point3 (&ends)[2], double solid_det, const BandFace& face, Point3 n,
                  double rise, double height);
  // The fluid face beyond the edge of kf's faces j and g_face in face j's plane (around the edge from kf through
  // g_face, on kf's side of the plane): its tetrahedra on kf's side (same) and across (other, -1 on the mesh's
  // boundary); false where no face of the ring lies in the plane.
  bool coplanar_beyond(int kf, int j, int g_face, int& same, int& other) const;
  // coplanar_beyond's answers kept for the edges met last (direct-mapped on (kf, j, g_face): the solid
  // tetrahedra near a fluid edge ask about it again for each of their pieces there)
  struct Beyond {
    int kf = -1, j, g_face, same, other;
    bool found;
  };
  mutable std::vector<Beyond> beyond_;
  bool walk_beyond(int kf, int j, int g_face, int& same, int& other) const;  // coplanar_beyond's ring walk
  // A band face's per-tetrahedron terms for the columns of kf's face with across (band_face's).
  void set_face_tets(BandFace& face, int kf, int across) const;
  // The straight image A (straight_): its slope along w, dA/dxi w; grad_xi (n . A); A(xi) relative to the origin.
  Point3 straight_slope(Point3 w) const;
  Point3 straight_gradient(Point3 n) const;
  Point3 straight_position(const ClippedImage3& image, Point3 xi) const;
  // The band where it crosses the faces of the solid tetrahedron (side_band3d.cpp): the fluid tetrahedra of the
  // pieces on each sub-face on a face of it (note_side_piece), then the band crossing each such sub-face, once
  // its pieces are done (finish).
  void note_side_piece(int kf, const Piece3& piece);
  struct SideFace {  // a sub-face, its frame and X on it (side_face)
    Point3 xi[3], y[3], nu, o, e1, e2, x, d[3], h_e1[3], h_e2[3], x_u, x_v, x_uu, x_uv, x_vv, lo, hi;
    Point3 edge_hessians[6];  // e^T H e along the sub-tetrahedron's edges
  };
  struct NearFace {  // a fluid face near a fluid tetrahedron, its corners, box and outward normal (face_normal)
    MeshFace3 face;
    Point3 v[3], lo, hi, n;
  };
  struct ColumnFrom {  // the columns of one fluid face on a sub-face
    const BandFace& face;
    Point3 n, y;
    double rise, d_in;
    int tet;
  };
  void side_face(const ClippedImage3& image, int sub, const QuadraticTerms& terms, SideFace& s) const;
  void side_band(const ClippedImage3& image, int sub, const QuadraticTerms& terms);
  void face_band(const ClippedImage3& image, int sub, const QuadraticTerms& terms, const SideFace& s,
                 const NearFace& f);
  void band_region(const ClippedImage3& image, const QuadraticTerms& terms, const SideFace& s, const ColumnFrom& c,
                   const double (*uv)[2], int m, int sign);
  const std::vector<NearFace>& near_faces(int kf);
  // The sub-tetrahedron's straight image A on the reference side (start): its edges from corner 0 in y, the
  // cofactors of its edges in xi (cofactor[i] = ex_(i+1) x ex_(i+2)) and det E_xi, from which dA/dxi = E_y E_xi^-1
  // and grad_xi (n . A) = E_xi^-T E_y^T n follow (band_face, face_band), once per image; with what the side band
  // reads of the whole solid tetrahedron.
  struct StraightImage {
    Point3 ey[3], cofactor[3];
    double det = 0;
    Point3 whole_e[3];  // the whole solid tetrahedron's affine interpolant: X(e_k) - X(0), k = 1, 2, 3
    double solid_det = 0;  // 6 |solid tetrahedron|
    bool whole = false;    // the sub-tetrahedron is the solid tetrahedron (subdivide 0)
    double size2 = 0;      // its longest edge's length squared, in xi
  };
  StraightImage straight_;
  int side_faces_ = 0, on_face_[4] = {-1, -1, -1, -1};  // on_face_[i]: T's face the sub-face opposite i lies on
  std::vector<int> side_kf_[4];
  std::vector<int> near_kf_;
  std::vector<std::vector<NearFace>> near_;
  std::vector<MeshFace3> touching_;
  std::vector<NearFace> candidates_;
  std::vector<unsigned> face_stamp_;  // 4 tet + face: == stamp_ once taken for the sub-face
  unsigned stamp_ = 0;
  std::vector<RegionPoint2> region_points_;
  // Under weighted_sum_terms and a fluid fitted at degree <= 2 (a quadratic map) the bands' points are summed as
  // moments (PointMoments3): a fluid face's columns in face_moments_ (add_column_moments), taken to the reference
  // coordinates of each of its two fluid tetrahedra and summed there per tetrahedron (moment_groups_, grouped as
  // the points across: add_face_moments), added to the block once per piece or image (add_band_moments): each
  // point's fluid monomials formed once, not once per tetrahedron.
  bool band_moments_ = false;
  PointMoments3 face_moments_;
  const LineRule* column_rule_ = nullptr;  // the columns' rule of the image's degree (start_band_moments)
  PointMoments3 beyond_moments_;  // an edge strip's columns in the face beyond the edge (edge_strip)
  struct MomentGroup {
    int kf = -1;
    bool fresh = false;  // just taken for kf (group_of): its moments to be zeroed
    long points = 0;
    std::vector<double> moments;  // PointMoments3::element_moments' layout
  };
  std::vector<MomentGroup> moment_groups_;
  int moment_groups_used_ = 0;
  std::vector<double> element_moments_;
  // Whether the bands go as moments here; if so, empty moments about the sub-tetrahedron's corner 0 (in xi).
  void start_band_moments(const ClippedImage3& image, const QuadraticTerms& terms);
  // A column's points (add_column's) into face_moments_ (or into): X(xi + t d) = x0 + t dd + t^2 d^T H d / 2.
  void add_column_moments(const BandFace& face, Point3 xi, Point3 x0, Point3 dd, double l, double column,
                          PointMoments3* into = nullptr);
  // face_moments_ (or from; settled) times sign into fluid tetrahedron kf's moments.
  void add_face_moments(const ClippedImage3& image, int kf, double sign, const PointMoments3* from = nullptr);
  void add_band_moments(const ClippedImage3& image, LocalBlock& block);
  // The face of kf (corner: its vertices; j: the face opposite vertex j) whose plane holds the piece's face
  // whose vertices share the planes common (Piece3::planes' bits), or -1; on_boundary when that face is on the
  // sub-tetrahedron's boundary.
  int fluid_plane(const ClippedImage3& image, const Point3 (&corner)[4], unsigned common, bool& on_boundary) const;
  // On the reference side: X at xi (relative to image.origin when it is not 0) and d[i] = dX/dxi_i.
  void reference_value(const ClippedImage3& image, Point3 xi, Point3& x, Point3 (&d)[3]) const;
  // X alone at xi, the same value as reference_value's.
  Point3 reference_position(const ClippedImage3& image, Point3 xi) const;
  // Adds reference point xi where X is x and dX/dxi is d, with its weight. No sign is checked here: det dX/dxi > 0
  // is certified on the whole solid tetrahedron before (MappedTet::prepare), and a band's column may end just
  // outside it, where only the polynomial's values count.
  void add_reference_point(const ClippedImage3& image, int kf, Point3 xi, Point3 x, const Point3 (&d)[3],
                           double weight);
  // The same without dX/ds (point_jacobians_ false: jac_ is not read).
  void add_reference_point(const ClippedImage3& image, int kf, Point3 xi, Point3 x, double weight);
  // dX/ds from d[i] = dX/dxi_i, into jac_.
  void add_jacobian(const ClippedImage3& image, const Point3 (&d)[3]);
  std::array<double, 9> jacobian(const ClippedImage3& image, const Point3 (&d)[3]) const;
  // The same with the point's reference coordinates in kf, eta, given.
  void add_reference_point(Point3 eta, Point3 xi, double weight);
  // Folds the weights and the chain rule's jacobian into the fluid functions read (with constant multiplier
  // gradients, into their gradients' sums instead).
  void weigh(const MappedTet& mt, int n, const std::vector<char>& read);
  void add_pairs(const MappedTet& mt, int n, bool twins, LocalBlock& block);
  // Constant multiplier gradients, an affine map and a fitted fluid basis: the fluid gradients are only
  // needed as their weighted sums along the points (PointValues3::evaluate_fluid_gradient_sums), to which
  // weigh applies the constant jacobian.
  bool deferred_chain(const MappedTet& mt) const {
    return constant_multiplier_gradients_ && mt.affine && integrand_.fluid.fitted();
  }
  // Constant multiplier gradients, a map that is neither affine nor quadratic (those go to weighted_sum_terms)
  // and a fluid basis fitted at degree 0 or 1: both gradients are constant, so sum_q w_q grad psi . (J_q^T grad
  // phi) = grad psi . (sum_q w_q J_q)^T grad phi: weigh sums the weighted jacobians once for all fluid functions
  // (PointValues3::evaluate_constant_gradients).
  bool constant_chain(const MappedTet& mt) const {
    return constant_multiplier_gradients_ && !mt.affine && constant_fluid_gradients_;
  }
  // A multiplier fitted at degree m <= 2 (not the listings' product) and a quadratic map: about a point c of
  // the batch, psi is a polynomial of degree m in r = xi - c and dX/ds(xi) = J(c) + sum_j r_j G_j is affine in r,
  // so every term is a weighted sum along the points of a fluid function or of its gradient, with the weights
  // w r^g, |g| <= m (add_weighted_sums): only the fluid's monomials are formed at the points.
  bool weighted_sum_terms(const MappedTet& mt) const {
    return polynomial_multiplier_ && !mt.affine && mt.fitted_degree() == 2;
  }
  void add_weighted_sums(const MappedTet& mt, int kf, int n, LocalBlock& block);
  // add_weighted_sums' terms once V_g and P_g (value_terms_ and gradient_terms_, sized by size_weighted_terms)
  // are formed about c, whichever way.
  void size_weighted_terms();
  void add_weighted_terms(const MappedTet& mt, Point3 c, LocalBlock& block);
  // The solid tetrahedron and the centre c whose multiplier terms (A_g, u_g) add_weighted_terms last formed: the
  // band's moments of every fluid tetrahedron of an image are taken about one centre (start() forgets them).
  int terms_k_ = -1;
  Point3 terms_c_;
  // A quadratic map's dX/ds(xi + r) = J + sum_j r_j G_j about xi: J = dX/ds(xi) and G_j = d(dX/ds)/dxi_j, each
  // formed by set_jacobian (of dX/dxi(xi) and of the hessian's columns), so each is of the size of dX/ds
  // whatever the mesh's units.
  void chain_matrices(const MappedTet& mt, Point3 xi, MapValue3& j, MapValue3 (&g)[3]) const;
  // c1 sum_q w_q dX/ds(q) over the gathered points (constant_chain), from jac_.
  void jacobian_sum(int n, double (&jw)[9]) const;
  void add_listing(const MappedTet& mt, int n, LocalBlock& block);

  const Integrand3& integrand_;
  CouplingReport& counts_;
  int fluid_functions_;
  bool gradients_, listing_;  // c1 != 0; and the listings' product
  // The chain rule with a multiplier fitted at degree 0 or 1 (gradients constant on a tetrahedron): weigh
  // sums each fluid function's weighted chain-rule gradients along the points (gradient_sums_: x, y, z).
  bool constant_multiplier_gradients_;
  bool constant_fluid_gradients_;  // a fluid basis fitted at degree 0 or 1
  bool polynomial_multiplier_;  // fitted bases, the multiplier at degree <= 2, not the listings' product
  // add_weighted_sums': the weights w r^g along the points; V_g and A_g; P_g and u_g
  std::vector<double> sum_weights_, value_terms_, gradient_terms_;
  std::vector<Point3> sum_points_;  // add_weighted_sums' r = xi - c
  std::vector<const double*> rows_;  // add_pairs': the pair's rows of values and gradients
  std::vector<double> products_;     // and their products
  // The gathered points carry dX/ds (jac_) where the map is not affine; on the reference side only where a
  // gradient term reads it at each point (not under weighted_sum_terms: add_weighted_sums).
  bool point_jacobians_ = true;
  std::vector<double> gradient_sums_;
  // The gathered points, as PointData's fields (jac_ as point_jacobians_ says).
  std::vector<Point3> eta_, xi_;
  std::vector<double> weight_;
  std::vector<std::array<double, 9>> jac_;
  void clear_points();
  const FluidSide3* fluid_;
  // Band points of fluid tetrahedra other than the piece's (gather_band's across a face plane, the side band's),
  // added after the piece's own (add_across): one group per fluid tetrahedron, in the order first met, each with
  // its points in the order added (dX/ds where the points carry it). tet_group_[kf] is kf's group while
  // tet_stamp_[kf] == tet_epoch_; groups_used_ of across_ are in use, the others keep their room.
  struct AcrossGroup {
    int kf = -1;
    bool fresh = false;  // just taken for kf (group_of): its points to be cleared
    std::vector<Point3> eta, xi;
    std::vector<double> weight;
    std::vector<std::array<double, 9>> jac;
  };
  std::vector<AcrossGroup> across_;
  int groups_used_ = 0;
  std::vector<int> tet_group_;
  std::vector<unsigned> tet_stamp_;
  unsigned tet_epoch_ = 0;
  // No group in use, a fresh epoch (before the points of an image's piece or of its side band).
  void begin_across();
  // Fluid tetrahedron kf's group among groups[0, used): the one taken in this epoch, else the next (fresh).
  template <class Group>
  Group& group_of(int kf, std::vector<Group>& groups, int& used);
  // A point of fluid tetrahedron kf among those across, with its dX/ds where the points carry it.
  void add_across_point(int kf, Point3 eta, Point3 xi, double weight, const std::array<double, 9>& jac);
  void add_across(const MappedTet& mt, LocalBlock& block);
  PointValues3 values_;
};

// Inline (in the header, for integrate_points3d.cpp and side_band3d.cpp): a call per point through the plugin's
// symbol table cost 12 % of a curved call.
inline void PointIntegrator3::reference_value(const ClippedImage3& image, Point3 xi, Point3& x, Point3 (&d)[3]) const {
  const MappedTet& mt = image.tetrahedron;
  if (image.origin != Point3()) {  // X(xi) - origin from the map's displacement, to the image's own precision
    mt.displacement(xi, x, d);
    x = x + (mt.origin() - image.origin);
  } else {
    mt.reference_derivatives(xi, x, d);
  }
}

inline Point3 PointIntegrator3::reference_position(const ClippedImage3& image, Point3 xi) const {
  const MappedTet& mt = image.tetrahedron;
  if (image.origin != Point3()) return mt.displacement_position(xi) + (mt.origin() - image.origin);
  return mt.position(xi);
}

// q(l) = c0 + c1 l + c2 l^2 along the column: c0 and c1 = n . dX/dl at xi; c2 = n . d^T H d / 2 for a quadratic
// map, else from q at the first-order step l1 = -c0 / c1 (where c0 + c1 l1 = 0); where the map's slope is far off
// the straight image's, that slope alone. The root continuous with -c0 / c1 as c2 -> 0, without cancellation.
inline double PointIntegrator3::column_root(const ClippedImage3& image, const BandFace& face, Point3 n, Point3 y,
                                            Point3 xi, Point3 x, Point3 dd, double rise) const {
  const double c0 = dot(n, x - y);
  if (c0 == 0) return 0;
  const double jn = dot(n, dd);
  double c1 = rise, c2 = 0;
  if (jn > 0.5 * rise) {
    c1 = jn;
    if (face.quadratic) {
      c2 = 0.5 * dot(n, face.dhd);
    } else {
      const double l1 = -c0 / c1;
      c2 = dot(n, reference_position(image, xi + l1 * face.d) - y) / (l1 * l1);
    }
  }
  const double disc = c1 * c1 - 4 * c0 * c2;
  return disc >= 0 ? -2 * c0 / (c1 + std::sqrt(disc)) : -c0 / c1;
}

}  // namespace dlmfsi
