// The quadrature method: a composite rule on each solid triangle, in the solid's reference coordinates,
//   int_T f(s) ds = sum_leaves sum_q |leaf| |T| w_q f(xi_q),   |T| = twice the solid triangle's area,
// with the true map at every point (the fluid triangle holding X(xi_q) found by a walk). A leaf is split
// into four (midpoints) while the images of its corners do not lie in one closed fluid triangle, down to
// tol of the triangle's area (depth ceil(log4(1 / tol)), at most 12). On a leaf inside one fluid triangle
// the integrand is a polynomial of degree p_solid + p_fluid * m for a map of degree m, which the rule
// integrates exactly (the product's degree where the map is affine; qforder overrides; a map of unknown
// degree gets nonlinear_rule_degree). Points whose image lies outside the fluid mesh count as area outside.
#pragma once
#include <vector>

#include "mesh/fluid_search.hpp"
#include "integration/integrate_points.hpp"

namespace dlmfsi {

class QuadratureMethod : public TriangleIntegrator {
 public:
  // search: on fluid's grid; qforder: the option (-1 automatic); tol: the leaves' smallest relative area;
  // map_degree: SolidMap::degree().
  QuadratureMethod(const FluidSide& fluid, FluidSearch& search, const Integrand& integrand, int map_degree,
                   int qforder, double tol, CouplingReport& counts);
  double integrate(const MappedTriangle& mt, LocalBlock& block) override;

 private:
  int rule_degree(const MappedTriangle& mt);
  // Do the three points lie in one closed fluid triangle?
  bool one_fluid_triangle(const Point img[3]);

  struct Leaf {
    Point ref[3], img[3];
    int depth;
  };

  const FluidSide& fluid_;
  FluidSearch& search_;
  int hint_ = 0;
  PointIntegrator points_;
  int product_degree_, fluid_degree_, multiplier_degree_, map_degree_, qforder_, max_depth_;
  CouplingReport& counts_;
  std::vector<Leaf> stack_;
};

}  // namespace dlmfsi
