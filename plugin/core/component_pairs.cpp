#include "component_pairs.hpp"

#include <algorithm>

namespace dlmfsi {

namespace {

// The local dofs that carry the listed components, sorted.
std::vector<int> used_dofs(const Basis& space, const std::vector<int>& components) {
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
std::vector<int> function_indices(const PolynomialBasis& fit, int components, int c, int first, int last) {
  const std::vector<int>& functions = fit.functions();
  std::vector<int> out;
  for (int d = first; d < last; ++d)
    out.push_back(static_cast<int>(std::find(functions.begin(), functions.end(), d * components + c) - functions.begin()));
  return out;
}

// Do the two lists name, one by one, the same functions or twins?
bool same_functions(const std::vector<int>& x, const std::vector<int>& y, const PolynomialBasis& fit) {
  auto representative = [&](int f) { return fit.twin(f) >= 0 ? fit.twin(f) : f; };
  if (x.size() != y.size()) return false;
  for (size_t i = 0; i < x.size(); ++i)
    if (representative(x[i]) != representative(y[i])) return false;
  return true;
}

}  // namespace

ComponentPairs::ComponentPairs(const Basis& fluid_space, const PolynomialBasis& fluid_fit,
                               const std::vector<int>& fluid_components, const Basis& multiplier,
                               const PolynomialBasis& multiplier_fit, const std::vector<int>& solid_components)
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
  for (size_t q = 0; q < pairs_.size(); ++q)
    for (size_t p = 0; p < q && pairs_[q].source < 0; ++p)
      if (pairs_[p].source < 0 && same_functions(pairs_[p].fluid_functions, pairs_[q].fluid_functions, fluid_fit) &&
          same_functions(pairs_[p].solid_functions, pairs_[q].solid_functions, multiplier_fit)) {
        pairs_[q].source = static_cast<int>(p);
        pairs_[p].copies.push_back(static_cast<int>(q));
      }
  fluid_read_.assign(fluid_fit.functions().size(), 0);
  fluid_read_by_sources_.assign(fluid_fit.functions().size(), 0);
  for (const ComponentPair& pair : pairs_)
    for (int f : pair.fluid_functions) {
      fluid_read_[f] = 1;
      if (pair.source < 0) fluid_read_by_sources_[f] = 1;
    }
}

}  // namespace dlmfsi
