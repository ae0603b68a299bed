// A finite element space seen one triangle at a time. The FreeFEM adapter implements it with the element's
// own basis evaluation, so the core works for any element without tables of its own.
#pragma once
#include <utility>
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

// A basis seen through a renumbering of its triangles: triangle k here is triangle original[k] of base.
class RenumberedBasis : public Basis {
 public:
  RenumberedBasis(const Basis& base, std::vector<int> original) : base_(base), original_(std::move(original)) {}
  int components() const override { return base_.components(); }
  int dof_count() const override { return base_.dof_count(); }
  int local_dofs() const override { return base_.local_dofs(); }
  void component_dofs(int c, int& first, int& last) const override { base_.component_dofs(c, first, last); }
  void dofs(int k, int* global) const override { base_.dofs(original_[k], global); }
  void evaluate(int k, Point xi, double* out) const override { base_.evaluate(original_[k], xi, out); }
  void values(int k, Point xi, double* out) const override { base_.values(original_[k], xi, out); }
  const std::vector<int>& original() const { return original_; }

 private:
  const Basis& base_;
  std::vector<int> original_;
};

// The polynomial degree of the basis on triangle k, found by probing: along three lines through the
// reference triangle, the (d+1)-th finite differences of every basis function vanish (to 1e-9 relative)
// for the smallest such d. Only the listed components count (all when the list is empty). Returns -1 when
// no degree up to 12 fits (not a polynomial element).
int polynomial_degree(const Basis& basis, const std::vector<int>& components = {}, int k = 0);

}  // namespace dlmfsi
