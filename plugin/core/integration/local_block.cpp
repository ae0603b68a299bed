#include "integration/local_block.hpp"

#include <algorithm>
#include <utility>

namespace dlmfsi {

LocalBlock::LocalBlock(int multiplier_dofs, std::vector<int> used_rows, int fluid_dofs,
                       std::vector<int> used_fluid_dofs)
    : rows_(multiplier_dofs), used_rows_(std::move(used_rows)), used_fluid_dofs_(std::move(used_fluid_dofs)),
      row_dofs_(multiplier_dofs), column_of_(fluid_dofs) {}

void LocalBlock::enter_fluid_element(const int* dofs) {
  const int* const used = used_fluid_dofs_.data();
  const int count = static_cast<int>(used_fluid_dofs_.size());
  for (int u = 0; u < count; ++u) {
    const int j = used[u], g = dofs[j];
    if (static_cast<size_t>(g) >= mark_of_dof_.size()) {
      const size_t size = std::max(static_cast<size_t>(g) + 1, 2 * mark_of_dof_.size());
      mark_of_dof_.resize(size, 0u);
      column_at_dof_.resize(size);
    }
    if (mark_of_dof_[g] != block_mark_) {  // a new column: its entries are zero already
      mark_of_dof_[g] = block_mark_;
      if (columns_ == static_cast<int>(column_dofs_.size())) add_column_room();
      column_at_dof_[g] = columns_;
      column_dofs_[columns_++] = g;
    }
    column_of_[j] = column_at_dof_[g];
  }
}

void LocalBlock::add_column_room() {
  const size_t room = std::max<size_t>(8, 2 * column_dofs_.size());
  column_dofs_.resize(room);
  entries_.resize(room * rows_, 0.0);
}

void LocalBlock::scatter(std::vector<Triplet>& out) {
  const size_t columns = static_cast<size_t>(columns_);
  if (columns == 0) return;  // no piece (the element lies outside the fluid mesh): entries_ may be empty
  for (int i : used_rows_) {
    const int row = row_dofs_[i];
    double* entry = &entries_[i];
    for (size_t c = 0; c < columns; ++c, entry += rows_) {
      if (*entry == 0.0) continue;
      // in place: a pushed temporary would be copied by a 16-byte load waiting for its two 8-byte stores
      out.emplace_back(row, column_dofs_[c], *entry);
      *entry = 0.0;
    }
  }
}

void LocalBlock::scatter(RowSum& sum, int w, std::vector<Triplet>& later) {
  const size_t columns = static_cast<size_t>(columns_);
  if (columns == 0) return;  // no piece (the element lies outside the fluid mesh): entries_ may be empty
  if (row_columns_.size() < columns) {
    row_columns_.resize(columns);
    row_values_.resize(columns);
  }
  for (int i : used_rows_) {
    const int row = row_dofs_[i];
    const bool is_later = sum.later(row);
    double* entry = &entries_[i];
    int n = 0;
    for (size_t c = 0; c < columns; ++c, entry += rows_) {
      if (*entry == 0.0) continue;
      if (is_later) {
        later.emplace_back(row, column_dofs_[c], *entry);
      } else {
        row_columns_[n] = column_dofs_[c];
        row_values_[n++] = *entry;
      }
      *entry = 0.0;
    }
    if (n > 0) sum.add_row(w, row, row_columns_.data(), row_values_.data(), n);
  }
}

void LocalBlock::scatter(InPlaceSum& sum, std::vector<Triplet>& misses, std::vector<Triplet>& later) {
  // The columns by increasing dof (a handful: insertion sort), so that each row's entries are found in one
  // pass along the matrix row. An entry's sum is over the solid elements in order whatever the order of the
  // columns within one element.
  const int columns = columns_;
  if (columns == 0) return;  // no piece (the element lies outside the fluid mesh): entries_ may be empty
  by_dof_.resize(columns);
  for (int c = 0; c < columns; ++c) {
    int j = c;
    for (; j > 0 && column_dofs_[by_dof_[j - 1]] > column_dofs_[c]; --j) by_dof_[j] = by_dof_[j - 1];
    by_dof_[j] = c;
  }
  const int* const dof_of = column_dofs_.data();
  for (int i : used_rows_) {
    const int row = row_dofs_[i];
    if (sum.later(row)) {
      double* entry = &entries_[i];
      for (int c = 0; c < columns; ++c, entry += rows_) {
        if (*entry == 0.0) continue;
        later.emplace_back(row, dof_of[c], *entry);
        *entry = 0.0;
      }
      continue;
    }
    const InPlaceSum::Row on_pattern = sum.row(row);
    const int* at = on_pattern.begin;
    double* const row_entries = entries_.data() + i;
    for (int c : by_dof_) {
      double& entry = row_entries[static_cast<size_t>(c) * rows_];
      if (entry == 0.0) continue;
      const int col = dof_of[c];
      while (at != on_pattern.end && *at < col) ++at;
      if (at != on_pattern.end && *at == col)
        sum.add_at(on_pattern, at, entry);
      else
        misses.emplace_back(row, col, entry);
      entry = 0.0;
    }
  }
}

}  // namespace dlmfsi
