// The map X that places the solid: its value and derivatives at a point of a solid triangle.
#pragma once
#include "point.hpp"

namespace dlmfsi {

struct MapValue {
  Point x;             // X(s)
  double jac[2][2];    // jac[a][b] = dX_a / ds_b, derivatives in the solid's reference coordinates s
};

class SolidMap {
 public:
  virtual ~SolidMap() = default;
  // X at reference point xi of solid triangle k. Must be safe to call from several threads at once.
  virtual MapValue evaluate(int k, Point xi) const = 0;
  // The polynomial degree of X on each triangle (1 to 6), or -1 when unknown or not polynomial.
  virtual int degree() const { return -1; }
  // The monomial coefficients (lattice.hpp order, degree()) of X and Y on triangle k in the reference
  // coordinates, or false to let the caller fit them from evaluate().
  virtual bool coefficients(int, double*, double*) const { return false; }
  // A hint that triangle k comes soon: its data brought towards the cache (nothing by default).
  virtual void prefetch(int) const {}
};

inline double det2(const double j[2][2]) { return j[0][0] * j[1][1] - j[0][1] * j[1][0]; }

}  // namespace dlmfsi
