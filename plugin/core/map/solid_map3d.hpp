// The map X that places a 3D solid, as the coupling sees it: X and its jacobian at a reference point of a
// solid tetrahedron, and what a polynomial map can tell about itself (its degree, coefficients, corners).
#pragma once
#include "point3.hpp"

namespace dlmfsi {

// The highest polynomial degree of a map fitted as a polynomial on each tetrahedron.
constexpr int kMaxMapDegree3 = 6;

struct MapValue3 {
  Point3 x;          // X(s)
  double jac[3][3];  // jac[a][b] = dX_a / ds_b, derivatives in the solid's reference coordinates s
};

inline double det3(const double j[3][3]) {
  return j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
         j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
}

class SolidMap3 {
 public:
  virtual ~SolidMap3() = default;
  // X at reference point xi of solid tetrahedron k. Must be safe to call from several threads at once.
  virtual MapValue3 evaluate(int k, Point3 xi) const = 0;
  // The polynomial degree of X on each tetrahedron (1 to 6), or -1 when unknown or not polynomial.
  virtual int degree() const { return -1; }
  // The monomial coefficients (lattice3d.hpp order, degree()) of X, Y and Z on tetrahedron k in the
  // reference coordinates, or false to let the caller fit them from evaluate().
  virtual bool coefficients(int, double*, double*, double*) const { return false; }
  // X at the four corners of tetrahedron k, exactly as the map's own values there (so that tetrahedra
  // sharing a vertex agree on its image bit for bit), or false to let the caller evaluate them.
  virtual bool corners(int, Point3*) const { return false; }
};

}  // namespace dlmfsi
