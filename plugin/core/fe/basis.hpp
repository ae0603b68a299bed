// A finite element space seen one element at a time, in 2D (triangles) or 3D (tetrahedra). The FreeFEM
// adapter implements it with the element's own basis evaluation, so the core works for any element
// without tables of its own.
#pragma once
#include <utility>
#include <vector>

#include "point.hpp"
#include "point3.hpp"

namespace dlmfsi {

// The reference point type of each dimension.
template <int D>
struct ReferencePoint;
template <>
struct ReferencePoint<2> {
  using type = Point;
};
template <>
struct ReferencePoint<3> {
  using type = Point3;
};

template <int D>
class BasisOf {
 public:
  using Reference = typename ReferencePoint<D>::type;
  static constexpr int kSlots = D + 1;  // per function and component: the value and D derivatives

  virtual ~BasisOf() = default;
  virtual int components() const = 0;
  virtual int dof_count() const = 0;   // global number of degrees of freedom
  virtual int local_dofs() const = 0;  // per element (the same on every element)
  // Local dofs [first, last) that carry component c (the same on every element).
  virtual void component_dofs(int c, int& first, int& last) const = 0;
  virtual void dofs(int k, int* global) const = 0;
  // Every element's dofs in one table, local_dofs() per element in element order (what dofs() gives), when
  // the basis keeps them so; otherwise null (the default).
  virtual const int* dof_table() const { return nullptr; }
  // Values and physical first derivatives of all local basis functions of element k at reference point xi
  // (coordinates (l1, l2[, l3]): x = p0 + l1 (p1 - p0) + l2 (p2 - p0) [+ l3 (p3 - p0)]):
  //   out[(df * components() + c) * kSlots + d], d = 0 value, 1 d/dx, 2 d/dy[, 3 d/dz].
  // Must be safe to call from several threads at once.
  virtual void evaluate(int k, Reference xi, double* out) const = 0;
  // The values alone, in the same layout (the derivative slots may be left unset). By default evaluate().
  virtual void values(int k, Reference xi, double* out) const { evaluate(k, xi, out); }
};

using Basis = BasisOf<2>;
using Basis3 = BasisOf<3>;

// A basis seen through a renumbering of its elements: element k here is element original[k] of base.
template <int D>
class RenumberedBasisOf : public BasisOf<D> {
 public:
  using Reference = typename BasisOf<D>::Reference;
  RenumberedBasisOf(const BasisOf<D>& base, std::vector<int> original) : base_(base), original_(std::move(original)) {}
  int components() const override { return base_.components(); }
  int dof_count() const override { return base_.dof_count(); }
  int local_dofs() const override { return base_.local_dofs(); }
  void component_dofs(int c, int& first, int& last) const override { base_.component_dofs(c, first, last); }
  void dofs(int k, int* global) const override { base_.dofs(original_[k], global); }
  void evaluate(int k, Reference xi, double* out) const override { base_.evaluate(original_[k], xi, out); }
  void values(int k, Reference xi, double* out) const override { base_.values(original_[k], xi, out); }
  const std::vector<int>& original() const { return original_; }

 private:
  const BasisOf<D>& base_;
  std::vector<int> original_;
};

using RenumberedBasis = RenumberedBasisOf<2>;
using RenumberedBasis3 = RenumberedBasisOf<3>;

// The polynomial degree of the basis on element k, found by probing: along three lines through the
// reference element, the (d+1)-th finite differences of every basis function vanish (to 1e-9 relative)
// for the smallest such d. Only the listed components count (all when the list is empty). Returns -1 when
// no degree up to 12 fits (not a polynomial element).
template <int D>
int polynomial_degree(const BasisOf<D>& basis, const std::vector<int>& components = {}, int k = 0);

}  // namespace dlmfsi
