// A finite element space seen one triangle at a time. The FreeFEM adapter implements it with the element's
// own basis evaluation, so the core works for any element without tables of its own.
#pragma once
#include <vector>

#include "point.hpp"

namespace dlmfsi {

class Basis {
 public:
  virtual ~Basis() = default;
  virtual int components() const = 0;
  virtual int dof_count() const = 0;   // global number of degrees of freedom
  virtual int local_dofs() const = 0;  // per triangle (the same on every triangle)
  // Local dofs [first, last) that carry component c (the same on every triangle).
  virtual void component_dofs(int c, int& first, int& last) const = 0;
  virtual void dofs(int k, int* global) const = 0;
  // Values and physical first derivatives of all local basis functions of triangle k at reference point xi
  // (coordinates (l1, l2): x = p0 + l1 (p1 - p0) + l2 (p2 - p0)):
  //   out[(df * components() + c) * 3 + d], d = 0 value, 1 d/dx, 2 d/dy.
  // Must be safe to call from several threads at once.
  virtual void evaluate(int k, Point xi, double* out) const = 0;
  // The values alone, in the same layout (the derivative slots may be left unset). By default evaluate().
  virtual void values(int k, Point xi, double* out) const { evaluate(k, xi, out); }
};

// The polynomial degree of the basis on triangle k, found by probing: along three lines through the
// reference triangle, the (d+1)-th finite differences of every basis function vanish (to 1e-9 relative)
// for the smallest such d. Only the listed components count (all when the list is empty). Returns -1 when
// no degree up to 12 fits (not a polynomial element).
int polynomial_degree(const Basis& basis, const std::vector<int>& components = {}, int k = 0);

}  // namespace dlmfsi
