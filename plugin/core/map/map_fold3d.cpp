#include "map/map_fold3d.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "errors.hpp"
#include "fe/lattice3d.hpp"

namespace dlmfsi {

DetSample jacobian_det(const MappedTet& mt, Point3 xi) {
  // d[i][a] = dX_a/dxi_i = sum_m c_a[m] f v_j, computed with an error <= (nm + degree + 1) eps A[i][a],
  // A[i][a] = sum_m |c_a[m] f v_j| >= |d[i][a]|; the triple product then errs by at most
  // ((1 + g)^3 - 1 + 4 eps) perm(A) with g that factor (perm: the permanent, the sum of the six
  // products of the determinant without signs).
  const int degree = mt.fitted_degree(), nm = monomial_count3(degree);
  const double* c[3] = {mt.coefficients(0), mt.coefficients(1), mt.coefficients(2)};
  double v[monomial_count3(MappedTet::kMaxDegree)];
  monomial_values3(degree, xi, v);
  double d[3][3] = {}, a[3][3] = {};
  const auto& derivative = monomial_derivatives3(degree);
  for (int m = 0; m < nm; ++m)
    for (int i = 0; i < 3; ++i) {
      const int j = derivative[m].index[i];
      if (j < 0) continue;
      const double dm = derivative[m].factor[i] * v[j];
      for (int b = 0; b < 3; ++b) {
        d[i][b] += c[b][m] * dm;
        a[i][b] += std::fabs(c[b][m] * dm);
      }
    }
  const double det = det3(d);
  const double perm = a[0][0] * (a[1][1] * a[2][2] + a[1][2] * a[2][1]) +
                      a[0][1] * (a[1][0] * a[2][2] + a[1][2] * a[2][0]) +
                      a[0][2] * (a[1][0] * a[2][1] + a[1][1] * a[2][0]);
  const double eps = std::numeric_limits<double>::epsilon();
  return {det, 4 * (nm + degree + 3) * eps * perm};
}

void check_fold(const MappedTet& mt) {
  Point3 where;
  JacobianSign sign = JacobianSign::Positive;
  if (mt.fitted_degree() >= 1) {
    sign = jacobian_sign3([&mt](Point3 xi) { return jacobian_det(mt, xi); }, 3 * (mt.fitted_degree() - 1), kFoldDepth,
                          kFoldTetrahedra, where);
  } else {
    // Not a polynomial: sampled on the degree-8 lattice.
    for (int p = 0; p < monomial_count3(8) && sign == JacobianSign::Positive; ++p) {
      Point3 x, d[3];
      mt.reference_derivatives(lattice_point3(8, p), x, d);
      if (!(dot(d[0], cross(d[1], d[2])) > 0)) {
        where = lattice_point3(8, p);
        sign = JacobianSign::Folds;
      }
    }
  }
  if (sign == JacobianSign::Positive) return;
  char at[160];
  std::snprintf(at, sizeof at, " at reference point (%.3g, %.3g, %.3g)", where.x, where.y, where.z);
  if (sign == JacobianSign::Folds)
    throw Error("the map folds solid tetrahedron " + std::to_string(mt.k) +
                " (its jacobian determinant is not positive" + at + ")");
  throw Error("the map nearly folds solid tetrahedron " + std::to_string(mt.k) +
              " (its jacobian determinant comes within about 1e-6 of zero" + at +
              ", or its certification needs more than " + std::to_string(kFoldTetrahedra) + " sub-tetrahedra)");
}

}  // namespace dlmfsi
