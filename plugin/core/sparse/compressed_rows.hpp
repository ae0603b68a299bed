// A range of the rows of a sparse matrix compressed from triplets.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "buffer_room.hpp"
#include "sparse/csr_matrix.hpp"

namespace dlmfsi {

// Rows first .. last - 1: their lengths, and their columns (sorted within each row) and values one row
// after the other. Duplicate (row, col) entries are summed in the order given (the parts in order, each in
// its order), whatever the range. The buffers are kept from one compression to the next (grown, never
// shrunk).
class CompressedRows {
 public:
  int first = 0, last = 0;
  std::vector<int> length;  // per row of the range
  BigVector<int> column;  // as CsrMatrix's (the two are swapped)
  BigVector<double> value;

  // Compresses the triplets of the count parts whose rows fall in the range (AllInRange: every triplet
  // given does, none to skip); linear in the number of triplets plus the sorts of each row's distinct
  // columns.
  template <bool AllInRange>
  void compress(int cols, const std::vector<Triplet>* parts, std::size_t count);

 private:
  // counting sort by row: offsets, fill pointers and the buckets' columns and values
  std::vector<int> offset_, fill_;
  RawRoom<int> bucket_col_;
  RawRoom<double> bucket_value_;
  std::vector<int> position_;  // per column: where it sits in the current row, if there
  std::vector<std::pair<int, double>> row_;
};

}  // namespace dlmfsi
