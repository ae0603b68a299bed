// The right-hand side of the method of characteristics on the fluid mesh: FreeFEM's
//   int2d(Th)(c * convect([u, v], dt, f1) * w1 + c * convect([u, v], dt, f2) * w2 + ...)
// for every test function w at once,
//   b_i = c * int_Omega sum_comp f_comp(X(x)) phi_{i,comp}(x) dx,
// X(x) the point reached from x by following the velocity (u, v) for a time dt (dt < 0: back to the foot of
// the characteristic through x). X is traced as FreeFEM's convect traces it, element by element: in each
// triangle the velocity at the point where the walk is, followed straight until an edge is met (the rest of
// the time goes on in the neighbour, with the velocity there) or the time is spent; the fluid boundary stops
// the walk where it meets it. The integral uses one rule on every triangle (degree 5 by default: the
// 7-point rule of FreeFEM's qf5pT, int2d's default).
//
// The field and the test functions are components of one space (the fluid side's), the velocity of the same
// space or of another one on the same mesh (a scalar field carried by a vector velocity); the velocity and the
// field are polynomials on each triangle, formed once per call, so that a point costs a few dozen operations
// rather than a basis evaluation.
#pragma once
#include <vector>

#include "point.hpp"
#include "sides/sides.hpp"

namespace dlmfsi {

struct CharacteristicsTerm {
  const double* velocity = nullptr;  // the velocity space's dof values: components u_component, v_component
  int u_component = 0, v_component = 1;
  const double* field = nullptr;     // the space's dof values
  std::vector<int> components{0, 1};  // of field, each tested with the same component of the space
  double dt = 0;                     // the time the velocity is followed for (negative: backwards)
  double c = 1;                      // the factor in front of the integral
  int degree = 5;                    // the rule's degree (rules.hpp)
};

struct CharacteristicsReport {
  long points = 0;           // quadrature points traced
  long crossings = 0;        // edges crossed by the walks in all
  long boundary_stops = 0;   // walks stopped by the fluid boundary
};

// Where a walk ends: triangle k of the side's mesh at reference point xi.
struct Foot {
  int k;
  Point xi;
  bool at_boundary;  // stopped by the fluid boundary before its time was spent
};

class Characteristics {
 public:
  // The side's basis must be fitted (a polynomial element) on the field's components, and the velocity side's
  // (side itself when velocity_side is null) on u_component and v_component; the two sides on one mesh (the
  // same triangles: the same Morton order). Throws Error naming what is wrong.
  Characteristics(const FluidSide& side, const CharacteristicsTerm& term, const FluidSide* velocity_side = nullptr);
  Characteristics(const Characteristics&) = delete;  // field_ may point at its own velocity_
  Characteristics& operator=(const Characteristics&) = delete;

  // The walk from reference point xi of triangle k (side numbering) for the term's time.
  Foot trace(int k, Point xi, CharacteristicsReport* report = nullptr) const;

  // b (side.space().dof_count() values) overwritten with the term's right-hand side.
  void assemble(double* b, CharacteristicsReport* report = nullptr) const;

 private:
  // Per triangle, the listed components of a finite element function (dof values) as polynomials in the
  // reference coordinates: terms_ coefficients per component, the components of triangle k together.
  static std::vector<double> local_polynomials(const FluidSide& side, const double* values,
                                               const std::vector<int>& comps);
  // NV, NF: the number of monomials of the velocity and of the field when fixed at compile time (1, 3, 6, 10:
  // degrees 0 to 3), else 0.
  template <int NV>
  Point velocity(int k, Point xi) const;
  template <int NV>
  Foot walk(int k, Point xi, CharacteristicsReport* report) const;
  template <int NV, int NF>
  void integrate(double* b, CharacteristicsReport* report) const;
  template <int NV>
  void integrate_field(double* b, CharacteristicsReport* report) const;

  const FluidSide& side_;
  const FluidSide& velocity_side_;
  CharacteristicsTerm term_;
  int terms_ = 0;                   // monomials per field component
  int velocity_terms_ = 0;          // monomials per velocity component
  double step_ = 0;                 // dt in the side's (scaled) coordinates
  std::vector<double> velocity_;    // u and v on each triangle
  std::vector<double> own_field_;   // the field's components on each triangle, unless it is the velocity
  const std::vector<double>* field_ = nullptr;  // own_field_ or velocity_
  std::vector<int> tested_;         // the fitted functions tested (indices in functions())
  std::vector<int> tested_slot_;    // the slot of each one's component in term_.components
};

}  // namespace dlmfsi
