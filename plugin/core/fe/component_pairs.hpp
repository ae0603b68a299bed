// The coupled component pairs laid out on the elements: fluid component fluid_components[p] with multiplier
// component solid_components[p], the local dofs that carry each, and where their functions sit among the
// fitted functions (PolynomialBasis::functions()). Built once per call and read by every thread; the same
// for triangles and tetrahedra.
#pragma once
#include <algorithm>
#include <vector>

#include "fe/basis.hpp"

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
  // Fit: the spaces' fitted bases (functions(), twin()) on the listed components.
  template <int D, class Fit>
  ComponentPairs(const BasisOf<D>& fluid_space, const Fit& fluid_fit, const std::vector<int>& fluid_components,
                 const BasisOf<D>& multiplier, const Fit& multiplier_fit, const std::vector<int>& solid_components);

  size_t size() const { return pairs_.size(); }
  const ComponentPair& operator[](size_t p) const { return pairs_[p]; }
  // The local dofs that carry a coupled component, sorted.
  const std::vector<int>& used_fluid_dofs() const { return used_fluid_dofs_; }
  const std::vector<int>& used_multiplier_dofs() const { return used_multiplier_dofs_; }
  // Per fitted fluid function: read by some pair; read by a pair that is not a copy.
  const std::vector<char>& fluid_read() const { return fluid_read_; }
  const std::vector<char>& fluid_read_by_sources() const { return fluid_read_by_sources_; }
  // The fitted multiplier functions read by some pair; by a pair that is not a copy (each once, ascending).
  const std::vector<int>& multiplier_read() const { return multiplier_read_; }
  const std::vector<int>& multiplier_read_by_sources() const { return multiplier_read_by_sources_; }

 private:
  std::vector<ComponentPair> pairs_;
  std::vector<int> used_fluid_dofs_, used_multiplier_dofs_;
  std::vector<char> fluid_read_, fluid_read_by_sources_;
  std::vector<int> multiplier_read_, multiplier_read_by_sources_;

  template <class Space>
  static std::vector<int> used_dofs(const Space& space, const std::vector<int>& components);
  template <class Fit>
  static std::vector<int> function_indices(const Fit& fit, int components, int c, int first, int last);
  // Sets the pairs' sources and copies, and the functions read, from each fitted function's representative
  // (its twin, or itself) on both sides.
  void find_twins(const std::vector<int>& fluid_representative, const std::vector<int>& multiplier_representative);
};

// The local dofs that carry the listed components, sorted.
template <class Space>
std::vector<int> ComponentPairs::used_dofs(const Space& space, const std::vector<int>& components) {
  std::vector<int> dofs;
  for (int c : components) {
    int first, last;
    space.component_dofs(c, first, last);
    for (int d = first; d < last; ++d) dofs.push_back(d);
  }
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

// The positions, among the fitted functions (dof * components + component), of component c on local dofs
// [first, last).
template <class Fit>
std::vector<int> ComponentPairs::function_indices(const Fit& fit, int components, int c, int first, int last) {
  const std::vector<int>& functions = fit.functions();
  std::vector<int> out;
  for (int d = first; d < last; ++d)
    out.push_back(static_cast<int>(std::find(functions.begin(), functions.end(), d * components + c) - functions.begin()));
  return out;
}

template <int D, class Fit>
ComponentPairs::ComponentPairs(const BasisOf<D>& fluid_space, const Fit& fluid_fit,
                               const std::vector<int>& fluid_components, const BasisOf<D>& multiplier,
                               const Fit& multiplier_fit, const std::vector<int>& solid_components)
    : used_fluid_dofs_(used_dofs(fluid_space, fluid_components)),
      used_multiplier_dofs_(used_dofs(multiplier, solid_components)) {
  for (size_t p = 0; p < fluid_components.size(); ++p) {
    ComponentPair pair;
    pair.fluid_component = fluid_components[p];
    pair.solid_component = solid_components[p];
    fluid_space.component_dofs(pair.fluid_component, pair.fluid_first, pair.fluid_last);
    multiplier.component_dofs(pair.solid_component, pair.solid_first, pair.solid_last);
    pair.fluid_functions = function_indices(fluid_fit, fluid_space.components(), pair.fluid_component,
                                            pair.fluid_first, pair.fluid_last);
    pair.solid_functions = function_indices(multiplier_fit, multiplier.components(), pair.solid_component,
                                            pair.solid_first, pair.solid_last);
    pairs_.push_back(pair);
  }
  auto representatives = [](const Fit& fit) {
    std::vector<int> out(fit.functions().size());
    for (int f = 0; f < static_cast<int>(out.size()); ++f) out[f] = fit.twin(f) >= 0 ? fit.twin(f) : f;
    return out;
  };
  find_twins(representatives(fluid_fit), representatives(multiplier_fit));
}

}  // namespace dlmfsi
