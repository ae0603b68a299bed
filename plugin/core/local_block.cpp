#include "local_block.hpp"

#include <algorithm>
#include <utility>

namespace dlmfsi {

LocalBlock::LocalBlock(int multiplier_dofs, std::vector<int> used_rows, int fluid_dofs,
                       std::vector<int> used_fluid_dofs)
    : rows_(multiplier_dofs), used_rows_(std::move(used_rows)), used_fluid_dofs_(std::move(used_fluid_dofs)),
      row_dofs_(multiplier_dofs), column_of_(fluid_dofs) {}

void LocalBlock::enter_fluid_element(const int* dofs) {
  for (int j : used_fluid_dofs_) {
    const int g = dofs[j];
    const auto it = std::find(column_dofs_.begin(), column_dofs_.end(), g);
    if (it != column_dofs_.end()) {
      column_of_[j] = static_cast<int>(it - column_dofs_.begin());
      continue;
    }
    column_dofs_.push_back(g);
    const size_t used = (column_dofs_.size() - 1) * rows_;  // the entries grow by one zero column
    if (entries_.size() < used + rows_) entries_.resize(2 * (used + rows_));
    std::fill(entries_.begin() + used, entries_.begin() + used + rows_, 0.0);
    column_of_[j] = static_cast<int>(column_dofs_.size()) - 1;
  }
}

void LocalBlock::scatter(std::vector<Triplet>& out) const {
  for (int i : used_rows_)
    for (size_t c = 0; c < column_dofs_.size(); ++c) {
      const double v = entries_[c * rows_ + i];
      if (v != 0.0) out.push_back({row_dofs_[i], column_dofs_[c], v});
    }
}

}  // namespace dlmfsi
