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
    const int columns = static_cast<int>(column_dofs_.size());
    int c = 0;
    while (c < columns && column_dofs_[c] != g) ++c;
    if (c == columns) {  // a new column: its entries are zero already
      column_dofs_.push_back(g);
      const size_t needed = column_dofs_.size() * rows_;
      if (entries_.size() < needed) entries_.resize(2 * needed, 0.0);
    }
    column_of_[j] = c;
  }
}

void LocalBlock::scatter(std::vector<Triplet>& out) {
  std::vector<Triplet>* const one[1] = {&out};
  scatter(one, RowRanges{1, 1});
}

void LocalBlock::scatter(std::vector<Triplet>* const* out, const RowRanges& ranges) {
  const size_t columns = column_dofs_.size();
  for (int i : used_rows_) {
    const int row = row_dofs_[i];
    std::vector<Triplet>& to = ranges.n == 1 ? *out[0] : *out[ranges.of(row)];
    double* entry = &entries_[i];
    for (size_t c = 0; c < columns; ++c, entry += rows_) {
      if (*entry == 0.0) continue;
      to.push_back({row, column_dofs_[c], *entry});
      *entry = 0.0;
    }
  }
}

void LocalBlock::scatter(InPlaceSum& sum, std::vector<Triplet>& misses) {
  const size_t columns = column_dofs_.size();
  for (int i : used_rows_) {
    const int row = row_dofs_[i];
    const InPlaceSum::Row on_pattern = sum.row(row);
    double* entry = &entries_[i];
    for (size_t c = 0; c < columns; ++c, entry += rows_) {
      if (*entry == 0.0) continue;
      if (!sum.add(on_pattern, column_dofs_[c], *entry)) misses.push_back({row, column_dofs_[c], *entry});
      *entry = 0.0;
    }
  }
}

}  // namespace dlmfsi
