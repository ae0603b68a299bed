// The exact method on curved images (maps of degree >= 2 and P1b maps), in the solid triangle's reference
// coordinates xi, with no chords. On a piece P = T ∩ X^-1(K), K a fluid triangle, the integrand
//   g(xi) = f_ij(s(xi)) |ds/dxi|
// is a polynomial of degree D = p_multiplier + p_fluid p_map (the fluid's polynomial on K extended beyond K,
// the multiplier's and the map's on T beyond T). It is integrated by a rule on the (D + 1)(D + 2)/2 Padua
// points of degree D in P's box [x0, x1] x [y0, y1] (u, v in [-1, 1] across it; unisolvent for degree D,
// with a slowly growing Lebesgue constant), with the weights w = V^-1 M that reproduce P's moments
//   M_ij = int_P L_i(u) L_j(v) dxi,  i + j <= D  (L: Legendre polynomials; V_ij,q = L_i(u_q) L_j(v_q)),
// exact for degree D on P: g = sum c_ij L_i L_j = sum_q g(q) (V^-1)_q,ij ... so sum_q w_q g(q) = sum c_ij M_ij.
// The moments come from Green's theorem,
//   M_ij = ∮_∂P G_ij dxi2,   G_ij = int_x0^xi1 L_i(u(σ)) dσ L_j(v) = hx Λ_i(u) L_j(v)   (Λ_i: L_i's integral),
// over ∂P, counter-clockwise, which is made of
//  - the parts of T's edges whose images lie in K: straight in xi, where G_ij dxi2 is a polynomial of degree
//    D + 1 in the edge's parameter, integrated by a Gauss rule exact for it;
//  - the preimages of the parts of K's edges inside X(T): xi(τ) = X^-1(y(τ)) along the edge (Newton), an
//    analytic curve where det dX/dxi > 0 (certified on T by check_fold), integrated by Gauss rules on
//    halves of the arc until the halves agree with the whole to round-off (spectral convergence).
// Both kinds come from the crossings of the image's edges (polynomials in their parameter, image_edges.hpp)
// with K's lines (roots_in). The parts are never joined into loops: each adds its own share, T lying on the
// left of its edges and K on the left of its edges (X keeps the orientation), so pieces with several
// components or holes need nothing special. An image edge along a fluid edge (coincident boundaries)
// counts once, as T's edge, where T and K lie on the same side of it, and not at all where they lie on
// opposite sides. The image's area outside the fluid mesh is its area (int_T det dX/dxi, exact) less the
// pieces'.
//
// Affine triangles, straight images (P1b maps) whose D is above kMaxStraightDegree, and maps or bases that are
// not polynomials of known degree go to the straight exact method (exact_method.hpp), which also keeps chords
// on request (subdivide=).
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "integration/integrate_batch.hpp"
#include "integration/integrate_points.hpp"
#include "geometry/polynomial_roots.hpp"
#include "map/image_edges.hpp"

namespace dlmfsi {

class CurvedMethod : public TriangleIntegrator {
 public:
  // straight: the method for affine triangles and maps not fitted.
  CurvedMethod(const FluidSide& fluid, const Integrand& integrand, std::unique_ptr<TriangleIntegrator> straight,
               CouplingReport& counts);
  double integrate(const MappedTriangle& mt, LocalBlock& block) override;

  // Polynomial bases of known degrees and a map of known degree 2 to kMaxPolynomialMapDegree (P1b maps: 3).
  static bool applies(const Integrand& integrand, int map_degree);

  // Gauss points on an arc: the polynomial part's need and 1 to kMaxArcExtraPoints more, chosen from the map's
  // nonlinearity on nearly straight arcs; on others kArcExtraPoints more, the halves compared with the whole.
  static constexpr int kArcExtraPoints = 2, kMaxArcExtraPoints = 6;
  // The halves' and the whole's shares of an arc agree to this (relative to the arc's size), or to the
  // round-off of reference coordinates: accepted.
  static constexpr double kArcTolerance = 1e-13, kArcRoundOff = 1e-15;
  static constexpr int kMaxArcDepth = 20;
  // Straight images (P1b maps) with D above this go to the straight method, whose pull-back rule is within
  // about 1e-13 there and cheaper when D is high (the Padua points grow as D^2 / 2: 28 at D = 6, 91 at
  // D = 12 for listing 5.1's P1b spaces under a P1b map).
  static constexpr int kMaxStraightDegree = 6;
  // The largest D: a multiplier and a fluid of degree 3 (FreeFEM's P3) under a map of degree 6.
  static constexpr int kMaxBoxDegree = 3 + 3 * kMaxPolynomialMapDegree;

 private:
  struct BoundaryPoint {
    Point xi;
    double weight;  // its share of ∮ G dxi2: w dxi2/dparameter
  };
  // The fluid triangle K of the piece, relative to the map's origin: corners w, edges e (inside on the left).
  struct FluidTriangle {
    Point w[3], e[3];
    // Line j along image edge i: q[i][j](t) = e_j x (X(xi(t)) - w_j), coefficients of t^k
    double q[3][3][kMaxPolynomialMapDegree + 1];
    bool coincident[3][3];  // image edge i along line j (q[i][j] below round-off)
    double at_corner[3][3];  // line j at the image of T's corner c, [j][c]: one number for both its edges
    double t[3][3 * kMaxRootsDegree + 2];  // breakpoints on T's edge i, breaks[i] of them
    int breaks[3];
    bool edge_meets[3];  // image edge i's control box meets K's box
  };
  struct Crossing {
    double tau;  // on K's edge
    Point xi;    // its reference point, on T's edge
  };
  // The Padua points of degree D and V^-1 (the class comment).
  void padua_rule(int degree);
  // The share of the piece T ∩ X^-1(K) (fluid triangle kf) added to block; returns its image's area.
  double piece(const MappedTriangle& mt, int kf, LocalBlock& block);
  // K's lines along T's image edges (fluid_triangle_: q, coincident, at_corner) and their crossings
  // (breakpoints on T's edges, crossings_ on K's).
  void find_crossings();
  // The parts of T's edges whose images lie in K, and the preimages of the parts of K's edges inside X(T): their
  // points into boundary_.
  void add_solid_edges();
  // K's edges (fluid triangle kf): an edge shared with a fluid triangle done before for this T takes its points,
  // reversed (one arc, not two); the others are computed by add_fluid_edge and kept for the neighbour.
  void add_fluid_edges(const MappedTriangle& mt, int kf);
  void add_fluid_edge(const MappedTriangle& mt, int j);
  // The piece's moments from boundary_, its Padua rule, the rule's points added to block; returns the image's
  // area.
  double integrate_piece(const MappedTriangle& mt, int kf, LocalBlock& block);
  // Appends the Gauss points of K's edge from w0 (relative to the map's origin) along e, for tau in
  // [ta, tb] whose ends have the reference points xa, xb.
  void arc(const MappedTriangle& mt, Point w0, Point e, double ta, double tb, Point xa, Point xb);
  // The points of the Gauss rule with `extra` points on [ta, tb] of that edge (false where Newton fails).
  bool arc_rule(const MappedTriangle& mt, Point w0, Point e, double ta, double tb, Point xa, Point xb, int extra,
                std::vector<BoundaryPoint>& points) const;
  // Adds the points' shares of three moments relative to ref, to compare rules by.
  void add_moments(const std::vector<BoundaryPoint>& points, Point ref, double moments[3]) const;
  // Is w (relative to the map's origin) inside X(T), at least `margin` inside in barycentric terms? xi: its
  // reference point, from `guess` or the nearest sample when guess is outside the triangle.
  bool inside_image(const MappedTriangle& mt, Point w, Point guess, double margin, Point& xi) const;

  const FluidSide& fluid_;
  const Integrand& integrand_;
  PointIntegrator points_;                  // the integrand at each point, or
  std::unique_ptr<BatchIntegrator> batch_;  // at all the rule's points at once (the chain rule or c1 = 0)
  std::unique_ptr<TriangleIntegrator> straight_;
  CouplingReport& counts_;
  int degree_ = -1;  // D, of the rules below
  std::vector<double> edge_nodes_, edge_weights_;
  std::vector<double> arc_nodes_[kMaxArcExtraPoints + 1], arc_weights_[kMaxArcExtraPoints + 1];  // by extra
  std::vector<BoundaryPoint> boundary_points_;
  std::vector<double> padua_u_, padua_v_;  // the Padua points of degree D in [-1, 1]^2
  std::vector<double> padua_inverse_;      // V^-1, a row per point
  std::vector<double> moments_;            // of the piece, (D + 1) per i
  // the piece's rule: points, reference points, weights (ds), dX/ds
  std::vector<Point> rule_y_, rule_xi_;
  std::vector<double> rule_weight_;
  std::vector<std::array<double, 4>> rule_jacobian_;
  ImageEdges edges_;
  double extent_ = 0;     // the image's box's larger width
  Point box_lo_, box_hi_;  // the box widened by 1e-10 extent_ (relative to the map's origin)
  Point sample_xi_[15], sample_x_[15];  // X - origin on the degree-4 lattice of T: Newton's starts
  std::vector<unsigned> stamp_of_;      // the fluid triangles met for this triangle
  std::vector<int> candidates_;
  unsigned stamp_ = 0;
  std::vector<BoundaryPoint> boundary_;
  // The fluid triangles done for this T: their edges' points in edge_store_, [begin, end) per edge.
  struct StoredEdges {
    int begin[3], end[3];
  };
  std::vector<unsigned> done_of_;  // stamp_ when done
  std::vector<int> slot_of_;       // its StoredEdges in done_
  std::vector<StoredEdges> done_;
  std::vector<BoundaryPoint> edge_store_;
  std::vector<Crossing> crossings_[3];
  FluidTriangle fluid_triangle_;
};

}  // namespace dlmfsi
