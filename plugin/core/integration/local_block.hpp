// The coupling's entries of one solid element while its pieces are integrated: one row per local
// multiplier dof, one column per global fluid dof of the fluid elements met so far.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "sparse/in_place_sum.hpp"
#include "sparse/row_sum.hpp"
#include "sparse/sparse.hpp"

namespace dlmfsi {

class LocalBlock {
 public:
  // multiplier_dofs and fluid_dofs: local dofs per element of each space; used_rows and used_fluid_dofs:
  // the local dofs that carry coupled components (the others are never read nor written).
  LocalBlock(int multiplier_dofs, std::vector<int> used_rows, int fluid_dofs, std::vector<int> used_fluid_dofs);

  // Starts the block of a solid element whose local multiplier dofs have the global dofs `dofs`: no
  // column yet.
  void start(const int* dofs) {
    std::copy(dofs, dofs + rows_, row_dofs_.begin());
    new_block();
  }
  // The same from the multiplier space's dofs of solid element k.
  template <class Space>
  void start(const Space& multiplier, int k) {
    multiplier.dofs(k, row_dofs_.data());
    new_block();
  }

  // Enters a fluid element whose local dofs have the global dofs `dofs`: each used local dof is given the
  // column of its global dof, a new zero column where the block has none yet (columns keep the order in
  // which their dofs first came). column(j) then addresses local dof j's column. Only the used rows of
  // the columns are written (the others stay zero).
  void enter_fluid_element(const int* dofs);

  // The entries of local fluid dof j's column (in the fluid element entered last), one per row.
  double* column(int j) { return &entries_[static_cast<size_t>(column_of_[j]) * rows_]; }

  // Appends (row dof, column dof, value) for the non-zero entries of the used rows, row by row and in
  // column order, and sets them back to zero. Entries never touched stay exactly zero (a multiplier
  // component paired with another fluid component) and are left out.
  void scatter(std::vector<Triplet>& out);

  // The same entries added to the summation on the last call's pattern where they are on it
  // (CsrBuilder::sum_on_last_pattern), the others appended to misses; the entries of the rows summed later
  // (InPlaceSum::later) appended to later.
  void scatter(InPlaceSum& sum, std::vector<Triplet>& misses, std::vector<Triplet>& later);

  // The same entries, in scatter(out)'s order, added to their rows in sum by writer w; the entries of the
  // rows summed later (RowSum::later) appended to later.
  void scatter(RowSum& sum, int w, std::vector<Triplet>& later);

  // Entries of one solid element for each used row and fluid column: an estimate of the triplets.
  size_t used_entries_per_fluid_element() const { return used_rows_.size() * used_fluid_dofs_.size(); }

 private:
  // No column yet: the columns' dofs cleared, the marks of the last block's dofs outdated.
  void new_block() {
    columns_ = 0;
    if (++block_mark_ == 0) {  // wrapped: clear the marks
      std::fill(mark_of_dof_.begin(), mark_of_dof_.end(), 0u);
      block_mark_ = 1;
    }
  }
  int rows_;
  std::vector<int> used_rows_, used_fluid_dofs_;
  std::vector<int> row_dofs_;     // global multiplier dof of each row
  // A column for each dof a fluid element entered brought; room for more columns in column_dofs_ and entries_.
  void add_column_room();
  int columns_ = 0;
  std::vector<int> column_dofs_;  // global fluid dof of each column, [0, columns_); its size is the room
  std::vector<int> column_of_;    // per local fluid dof of the element entered last: its column
  // Per global fluid dof: its column in this block when mark_of_dof_[dof] == block_mark_ (grown on demand).
  std::vector<int> column_at_dof_;
  std::vector<unsigned> mark_of_dof_;
  unsigned block_mark_ = 1;  // the marks start at 0: no dof marked
  std::vector<int> by_dof_;       // scatter(InPlaceSum&, ...): the columns by increasing dof
  std::vector<int> row_columns_;  // scatter(RowSum&, ...): one row's non-zero entries
  std::vector<double> row_values_;
  // Column-major, rows_ per column, room for column_dofs_.size() columns; zero outside the current element's
  // columns (scatter clears what it reads), so that a new column starts at zero.
  std::vector<double> entries_;
};

}  // namespace dlmfsi
