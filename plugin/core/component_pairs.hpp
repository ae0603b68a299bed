// The coupled component pairs laid out on the elements: fluid component fluid_components[p] with multiplier
// component solid_components[p], the local dofs that carry each, and where their functions sit among the
// fitted functions (PolynomialBasis::functions()). Built once per call and read by every thread.
#pragma once
#include <vector>

#include "basis.hpp"
#include "polynomial_basis.hpp"

namespace dlmfsi {

struct ComponentPair {
  int fluid_component, solid_component;
  int fluid_first, fluid_last;  // local fluid dofs [first, last) carrying the fluid component
  int solid_first, solid_last;  // local multiplier dofs [first, last) carrying the multiplier component
  // For each of those dofs, in order: the index of its function among the fitted functions.
  std::vector<int> fluid_functions, solid_functions;
  // Twins: on elements of the shared fits (PolynomialBasis::shared) a pair whose functions are, one by
  // one, twins of an earlier pair's (PolynomialBasis::twin) has that pair's sums bit for bit.
  int source = -1;           // the earlier pair this one repeats, or -1
  std::vector<int> copies;   // the later pairs that repeat this one
};

class ComponentPairs {
 public:
  ComponentPairs(const Basis& fluid_space, const PolynomialBasis& fluid_fit, const std::vector<int>& fluid_components,
                 const Basis& multiplier, const PolynomialBasis& multiplier_fit,
                 const std::vector<int>& solid_components);

  size_t size() const { return pairs_.size(); }
  const ComponentPair& operator[](size_t p) const { return pairs_[p]; }
  // The local dofs that carry a coupled component, sorted.
  const std::vector<int>& used_fluid_dofs() const { return used_fluid_dofs_; }
  const std::vector<int>& used_multiplier_dofs() const { return used_multiplier_dofs_; }
  // Per fitted fluid function: read by some pair; read by a pair that is not a copy.
  const std::vector<char>& fluid_read() const { return fluid_read_; }
  const std::vector<char>& fluid_read_by_sources() const { return fluid_read_by_sources_; }

 private:
  std::vector<ComponentPair> pairs_;
  std::vector<int> used_fluid_dofs_, used_multiplier_dofs_;
  std::vector<char> fluid_read_, fluid_read_by_sources_;
};

}  // namespace dlmfsi
