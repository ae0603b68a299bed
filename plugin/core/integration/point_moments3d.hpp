// Weighted sums over points regrouped as moments in the image's coordinates, for points that count in several
// fluid tetrahedra (the bands': each column in the two tetrahedra of its fluid face). A fluid function
// fitted at degree p is a polynomial in its element's reference coordinates eta, affine in x:
// eta = eta_c + J (x - x_c). So the sums that add_weighted_sums forms point by point,
//   sum_q w_q (xi_q - c)^g phi(eta_q)   for every multiplier monomial g (|g| <= m) and fluid function phi,
// follow, once per element whatever the number of points, from the moments
//   M[g][b] = sum_q w_q (xi_q - c)^g r_q^b,   r = (x - x_c) / L,   |b| <= p,
// L the points' spread about x_c (so that r is of size 1 whatever the mesh's units): (eta_c + J L r)^a is a
// polynomial in r, T[a][b] its coefficients (monomial a its parent's times one coordinate, monomial_parents3),
// and the element's moments are mu[g][a] = sum_b T[a][b] M[g][b].
#pragma once
#include <cstddef>
#include <vector>

#include "point3.hpp"

namespace dlmfsi {

class PointMoments3 {
 public:
  // Empty moments of multiplier degree m and fluid degree p about c (in xi); x_c: the mean x of the points of
  // the first settle(), L their spread.
  void reset(int m, int p, Point3 c);
  // A point (kept until settle()).
  void add(Point3 xi, Point3 x, double w) {
    if (n_ == w_.size()) grow();
    xi_[n_] = xi;
    x_[n_] = x;
    w_[n_++] = w;
  }
  // The points added since into the moments: as products of rows along them (row_products), or point by point
  // where both degrees are <= 1 (add_linear, add_paired) and for a linear multiplier against a quadratic fluid
  // (add_paired).
  void settle();
  // Empty again, about the same c.
  void clear();
  long points() const { return points_ + static_cast<long>(n_); }
  Point3 centre() const { return c_; }
  Point3 x_centre() const { return x_c_; }
  // mu[g nm + a] (nm = monomial_count3(p)): the moments (settled) in the element coordinates
  // eta = eta_c + J (x - x_c), J = d eta / d x row-major, eta_c those of x_c.
  void element_moments(Point3 eta_c, const double* j, double* mu) const;

 private:
  int m_ = 0, p_ = 0, cg_ = 1, cb_ = 1;
  long points_ = 0;
  Point3 c_, x_c_;
  double scale_ = 1;  // L
  std::vector<double> moment_;  // M[g cb + b]
  // the points not settled: the first n_ of each (the buffers only grow, so that a settle() and the points after it
  // write into memory already there)
  std::vector<Point3> xi_, x_;
  std::vector<double> w_;
  std::size_t n_ = 0;
  std::vector<double> rows_, product_;  // settle's rows (cg_ then cb_) and their products (grown as the points)
  void grow();
  // The moments of degree <= 1 in xi and in r (CG, CB = 1 or 4, not both 4) of the n points, summed point by point.
  template <int CG, int CB>
  void add_linear(std::size_t n, double to_unit);
  // The moments of degree <= 1 in xi and <= 1 (P = 2) or <= 2 (P = 5) in r of the n points, summed point by point,
  // the 2 P monomials of r in P pairs of lanes.
  template <int P>
  void add_paired(std::size_t n, double to_unit);
  mutable std::vector<double> expansion_;  // T[a cb + b]
};

}  // namespace dlmfsi
