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

namespace dlmfsi {

struct LineRule;

class FluidSide3;

class PointIntegrator3 : public PieceIntegrator3 {
 public:
  // fluid: its mesh's adjacency and dofs, for the band on the reference side where a sub-tetrahedron's face lies
  // in a fluid face plane (gather_band); without it such faces are taken as faces inside the sub-tetrahedron.
  PointIntegrator3(const Integrand3& integrand, CouplingReport& counts, const FluidSide3* fluid = nullptr);
  double integrate(const ClippedImage3& image, int kf, const Piece3& piece, LocalBlock& block) override;

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
    Point3 grad;  // grad_xi (n . A) of the sub-tetrahedron's straight image
    bool quadratic = false;
    int across = -1;
  };
  // The columns of kf's face plane j (its fluid neighbour across): face, the plane's outward normal n (n . y grows
  // out of kf), rise = d(n . A)/dl along the axis and height = d . nu; false where the plane's preimage under the
  // sub-tetrahedron's straight image has no gradient.
  bool band_face(const ClippedImage3& image, int kf, int j, int across, const QuadraticTerms& terms, BandFace& face,
                 Point3& n, double& rise, double& height) const;
  // The band where it meets the solid tetrahedron's faces (gather_reference_side, after gather_band): columns
  // from its faces that add the part of the band no column from a piece's face in it reaches and take back the
  // part beyond the tetrahedron that those columns covered, so that each solid tetrahedron integrates the band
  // inside itself with its own polynomials.
  void gather_side_band(const ClippedImage3& image, int kf, const Piece3& piece, const Point3* xi_corner,
                        double solid_det, const QuadraticTerms& terms);
  // gather_side_band's piece: the rules of its lines, kf's corners, the face of the solid tetrahedron T each face
  // of the sub-tetrahedron lies on (on_face[i] for the face opposite its corner i, or -1), and the face plane of kf
  // that holds the straight image of the face of T being swept (in_plane, or -1).
  struct SideContext {
    SideContext(const ClippedImage3& image_, int kf_, const Piece3& piece_, const Point3* xi_corner_,
                double solid_det_, const QuadraticTerms& terms_)
        : image(image_), kf(kf_), piece(piece_), xi_corner(xi_corner_), solid_det(solid_det_), terms(terms_) {}
    const ClippedImage3& image;
    int kf;
    const Piece3& piece;
    const Point3* xi_corner;
    double solid_det;
    const QuadraticTerms& terms;
    int on_face[4] = {-1, -1, -1, -1};
    Point3 corner[4];
    const LineRule* along_trace = nullptr;
    const LineRule* across_trace = nullptr;
    const LineRule* along_edge = nullptr;
    Point3 edge_hessians[6];  // e^T H e along the sub-tetrahedron's six edges e (a quadratic map)
    int in_plane = -1;
  };
  // One plane of kf swept on a face sigma of T: its columns (face), outward normal n, a point y of it (in the
  // image's coordinates) and dir, the unit ascent of n . A_T within sigma (in xi).
  struct SideLine {
    int j = -1, across = -1;
    BandFace face;
    Point3 n, y, dir;
    double reach = -1;  // band_may_reach's bound on |n . (X - A)|, on first use
  };
  // An edge of T through a point (edge_line): the line's direction along, the far corner's barycentric s0 at the
  // point, n . X - c = q0 + q1 tau + q2 tau^2 along it and its roots, the sub-tetrahedron's part [ta, tb] with n .
  // A - c from qa to qb there and 0 at tau_p.
  struct EdgeLine {
    int c1 = -1, roots = 0;
    Point3 along;
    double s0, q0, q1, q2, root[2], ta, tb, qa, qb, tau_p;
    // The first of Q's crossings, P's (unless from_p: the start is P's) and the part's end from t in direction
    // (+1, -1); at_p when it is P's.
    double end(double t, int direction, bool& at_p, bool from_p) const;
  };
  bool side_line(const SideContext& c, int sigma, int j, SideLine& line) const;
  bool far_lacks(const SideContext& c, int j) const;
  bool band_may_reach(const SideContext& c, SideLine& line, Point3 a, Point3 b) const;
  void side_trace(const SideContext& c, int sigma, int u, int v, int j, const SideLine& line);
  bool edge_line(const SideContext& c, Point3 xi0, int sigma, int edge_face, const SideLine& line, EdgeLine& e) const;
  void side_edge_component(const SideContext& c, int sigma, int edge_face, Point3 xi0, const SideLine& line,
                           bool far_side);
  void side_edge_local(const SideContext& c, int sigma, int edge_face, int u, int v, const SideLine& line);
  void side_sweep(const SideContext& c, int sigma, const SideLine& line, const LineRule& along, Point3 y, Point3 p0,
                  Point3 edge, double t0, double t1, Point3 w, double side, double sign);
  // The root nearest 0 of n . (X(xi + r w) - y) (X = x and dX/dr = slope at xi), quadratic in r for a P2 map
  // (terms: its hessian); NaN where it has none.
  double plane_root(const ClippedImage3& image, Point3 n, Point3 y, Point3 xi, Point3 x, Point3 slope, Point3 w,
                    const QuadraticTerms& terms) const;
  // The points of one column (gather_band): from xi, where X is x0, dX/dl is dd and dX/dxi is D (where the
  // points carry it), to l, the column's weight int_face's l height dA; in kf, and with the opposite weight in
  // the fluid tetrahedron across (across_).
  void add_column(const ClippedImage3& image, int kf, const BandFace& face, Point3 xi, Point3 x0, Point3 dd,
                  const Point3 (&D)[3], double l, double column);
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
  // Band points of the fluid tetrahedron across a face plane of the piece's (gather_band), added after the
  // piece's own (add_across); their dX/ds, where the points carry it, at across_jac_[jac].
  struct AcrossPoint {
    int kf, jac;
    Point3 eta, xi;
    double weight;
  };
  std::vector<AcrossPoint> across_;
  std::vector<std::array<double, 9>> across_jac_;
  void add_across(const MappedTet& mt, LocalBlock& block);
  PointValues3 values_;
};

}  // namespace dlmfsi
