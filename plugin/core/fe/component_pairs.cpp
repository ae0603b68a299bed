#include "fe/component_pairs.hpp"

#include <algorithm>

namespace dlmfsi {

void ComponentPairs::find_twins(const std::vector<int>& fluid_representative,
                                const std::vector<int>& multiplier_representative) {
  // Do the two lists name, one by one, functions of the same representatives?
  auto same = [](const std::vector<int>& x, const std::vector<int>& y, const std::vector<int>& representative) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
      if (representative[x[i]] != representative[y[i]]) return false;
    return true;
  };
  for (size_t q = 0; q < pairs_.size(); ++q)
    for (size_t p = 0; p < q && pairs_[q].source < 0; ++p)
      if (pairs_[p].source < 0 && same(pairs_[p].fluid_functions, pairs_[q].fluid_functions, fluid_representative) &&
          same(pairs_[p].solid_functions, pairs_[q].solid_functions, multiplier_representative)) {
        pairs_[q].source = static_cast<int>(p);
        pairs_[p].copies.push_back(static_cast<int>(q));
      }
  fluid_read_.assign(fluid_representative.size(), 0);
  fluid_read_by_sources_.assign(fluid_representative.size(), 0);
  for (const ComponentPair& pair : pairs_)
    for (int f : pair.fluid_functions) {
      fluid_read_[f] = 1;
      if (pair.source < 0) fluid_read_by_sources_[f] = 1;
    }
  multiplier_read_.clear();
  multiplier_read_by_sources_.clear();
  for (const ComponentPair& pair : pairs_)
    for (int f : pair.solid_functions) {
      multiplier_read_.push_back(f);
      if (pair.source < 0) multiplier_read_by_sources_.push_back(f);
    }
  for (std::vector<int>* read : {&multiplier_read_, &multiplier_read_by_sources_}) {
    std::sort(read->begin(), read->end());
    read->erase(std::unique(read->begin(), read->end()), read->end());
  }
}

}  // namespace dlmfsi
