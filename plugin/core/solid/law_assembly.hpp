// The elastic law's part of the solid block, assembled over the solid mesh with a given rule (edp/lib/solid.idp:
// the law linearized about the map [XL, YL]):
//   K_ab = sum_T |T| sum_q w_q  DP(Fl)[Grad phi_b] : Grad phi_a     (row a: the test function),
//   r_a  = sum_T |T| sum_q w_q  (DP(Fl)[Fl] - P(Fl)) : Grad phi_a,
// with Fl = Grad [XL, YL] at the rule's point x_q of T, phi the functions of the space's two components that
// hold the position (Grad phi: the 2x2 gradient of those two components), solid/law.hpp's tangent and stress.
// Every other entry of the space is zero. The gradients at the rule's points come from the Basis itself
// (no fit), tabulated once per space and rule.
#pragma once
#include <vector>

#include "fe/basis.hpp"
#include "fe/rules.hpp"
#include "solid/law.hpp"
#include "sparse/csr_matrix.hpp"
#include "sparse/in_place_sum.hpp"
#include "sparse/sparse.hpp"  // compress

namespace dlmfsi {

// The physical first derivatives of the listed components (one or two) of a basis at a rule's points, on
// every element: only the local functions that carry one of them.
class RuleGradients {
 public:
  // elements: the mesh's triangles (the basis's elements); components: distinct, in [0, components()).
  RuleGradients(const Basis& basis, int elements, const std::vector<int>& components,
                const std::vector<RulePoint>& rule);
  int elements() const { return elements_; }
  int points() const { return points_; }
  int functions() const { return static_cast<int>(local_.size()); }
  int components() const { return components_; }
  int dof_count() const { return dof_count_; }
  // The global dofs of element k's functions (functions() of them).
  const int* dofs(int k) const { return &dofs_[static_cast<size_t>(k) * local_.size()]; }
  // At point q of element k, function f: d/dx, d/dy of the first listed component, then of the second:
  // at(k, q) + (f * components() + c) * 2 + d.
  const double* at(int k, int q) const { return &gradients_[(static_cast<size_t>(k) * points_ + q) * stride_]; }

 private:
  int elements_, points_, components_, dof_count_;
  std::vector<int> local_;  // the local dofs that carry a listed component
  size_t stride_;           // entries per (element, point)
  std::vector<int> dofs_;
  std::vector<double> gradients_;
};

// One component of the linearization map: an FE function given by its space's gradients (one component
// tabulated) and its coefficients (dof_count() of them).
struct MapComponent {
  const RuleGradients* gradients;
  const double* coefficients;
};

struct LawProblem {
  SolidLaw law = SolidLaw::Svk;
  LawConstants constants;
  const RuleGradients* position = nullptr;  // two components: the position's x and y
  MapComponent x{}, y{};                    // XL, YL on the same mesh and rule
  const std::vector<RulePoint>* rule = nullptr;
  const std::vector<double>* areas = nullptr;  // |T| per element
  // The elements first .. last - 1 only (a share of a distributed assembly; last < 0: to the end). The
  // shares of a split add up to the whole matrix and right-hand side.
  int first = 0, last = -1;
};

// Keeps the matrix's buffers from call to call (a time loop takes no fresh memory).
class LawAssembly {
 public:
  // K (dof_count x dof_count of the position's space), plus the triplets of plus when given (entries on
  // the same place summed, K's first). Errors: inconsistent inputs (plus out of range); nh with J <= 0 at
  // a rule point (naming the element).
  const CsrMatrix& matrix(const LawProblem& p, const std::vector<Triplet>* plus = nullptr);
  // r (dof_count entries, set; zero off the position's dofs).
  void rhs(const LawProblem& p, std::vector<double>& out) const;

 private:
  // The matrix of the triplets (K's, then plus's): summed in place on the last call's pattern (InPlaceSum:
  // compress's sums, bit for bit), compressed again when the pattern changed.
  const CsrMatrix& sum(int n);

  std::vector<std::vector<Triplet>> triplets_ = std::vector<std::vector<Triplet>>(2);  // K's, plus's
  CsrMatrix matrix_;
  InPlaceSum in_place_;
};

}  // namespace dlmfsi
