// The quadrature method for tetrahedra: a composite rule in the solid's reference coordinates,
//   int_T f(s) ds = sum_sub sum_q |T| 6|sub| w_q f(xi_q),   |T| the solid tetrahedron's volume,
// over the 8^subdivide tetrahedra of the red-refined reference tetrahedron (reference_subdivision), with the
// true map at every point: the fluid tetrahedron holding X(xi_q) is found by a walk (none is skipped: a point
// whose image lies outside the fluid mesh counts as volume outside, an error beyond outsidetol). The rule's
// degree is the product's where the map is affine, p_multiplier + p_fluid * m for a polynomial map of degree
// m (qforder overrides): exact wherever the image of a sub-tetrahedron lies in one fluid tetrahedron, a
// quadrature error where it crosses the fluid's faces (the fluid functions' kinks). With qforder 2 or 5 the
// points are those of FreeFEM's qfV2 and qfV5. There are no adaptive leaves as in 2D (tol): in 3D the leaves
// that straddle a fluid face grow like 4^depth, and the exact method is cheaper than resolving them.
#pragma once
#include <vector>

#include "integration/integrate_points3d.hpp"
#include "integration/integrator3d.hpp"

namespace dlmfsi {

class QuadratureMethod3 : public TetrahedronIntegrator {
 public:
  // search: on fluid's grid; qforder, subdivide: the options (-1: automatic, and 0 subdivisions).
  QuadratureMethod3(const FluidSide3& fluid, FluidSearch3& search, const Integrand3& integrand, int qforder,
                    int subdivide, CouplingReport& counts);
  double integrate(const MappedTet& mt, LocalBlock& block) override;

 private:
  int rule_degree(const MappedTet& mt);
  // The fluid tetrahedron holding y (-1: outside the fluid mesh) and y's reference coordinates there.
  int find(Point3 y, Point3& eta);

  struct Located {
    int kf;
    PointIntegrator3::PointData point;
  };

  const FluidSide3& fluid_;
  FluidSearch3& search_;
  const Integrand3& integrand_;
  int hint_ = 0;
  int qforder_, subdivide_;
  PointIntegrator3 points_;
  CouplingReport& counts_;
  std::vector<Located> located_;
  std::vector<PointIntegrator3::PointData> group_;
};

}  // namespace dlmfsi
