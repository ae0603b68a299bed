// Compressed rows from the triplets of an assembly (csr_matrix.hpp), with buffers kept across a time loop.
#pragma once
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "sparse/compressed_rows.hpp"
#include "sparse/csr_matrix.hpp"
#include "sparse/in_place_sum.hpp"
#include "sparse/row_sum.hpp"

namespace dlmfsi {

// Compressed rows from triplets, the buffers kept from one build to the next (grown, never shrunk), so
// that a time loop takes no fresh memory. Duplicate (row, col) entries are summed in the order given (the
// parts in order, each in its order) and the columns sorted within each row (CompressedRows). When the
// triplets fall on the last build's pattern and cover all of it, the values are summed in place in the
// same order (InPlaceSum: the same sums bit for bit) and the pattern is kept. With threads, each
// compresses a range of rows (reading every triplet, in order): the same matrix for any thread count.
class CsrBuilder {
 public:
  CsrBuilder() = default;
  CsrBuilder(const CsrBuilder&) = delete;
  CsrBuilder& operator=(const CsrBuilder&) = delete;
  const CsrMatrix& build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts, int threads = 1);
  // The next build entry by entry (one thread), summed straight into the last build's values where the
  // entry is on its pattern (InPlaceSum::add); an entry that is not goes to a list of triplets instead, the
  // misses. Every contribution to an entry takes the same way, in order, so that each sum is compress's.
  // Returns the summation, or nullptr when there is no last matrix of these sizes (then build as usual).
  InPlaceSum* sum_on_last_pattern(int rows, int cols);
  // The matrix of the entries set in place (the last pattern's others dropped) and of the compressed
  // misses: build's matrix of all the contributions in the order they came, bit for bit. The pattern is
  // kept when there are no misses and every entry was set. With threads (each summing the rows only it adds
  // to, InPlaceSum::later_rows): their later rows' triplets in later[0 .. threads - 1] are summed here in
  // order, and the misses are in misses[0 .. threads - 1], misses[threads] taking the later rows' ones. An
  // entry's contributions then all come from one list, in order. The threads then merge ranges of rows.
  const CsrMatrix& build_on_last_pattern(std::vector<Triplet>* misses, const std::vector<Triplet>* later = nullptr,
                                         int threads = 1);
  // A build without a last pattern, summed row by row as the entries come (RowSum: no triplets but the
  // spilled rows'), by `writers` threads; then build_summed_rows. The same matrix as build's of the same
  // contributions in the same order (writer 0's elements, then writer 1's, ...), bit for bit.
  RowSum* sum_by_rows(int rows, int cols, int writers);
  // The matrix of the rows summed; with threads, the later rows' triplets (RowSum::later_rows) in
  // later[0 .. threads - 1] added first, in order.
  const CsrMatrix& build_summed_rows(const std::vector<Triplet>* later = nullptr, int threads = 1);
  const CsrMatrix& matrix() const { return matrix_; }
  // Did the last build keep the pattern of the one before?
  bool kept_pattern() const { return kept_pattern_; }
  // The matrix moved out (the builder starts afresh).
  CsrMatrix release() { return std::exchange(matrix_, CsrMatrix{}); }

 private:
  // Each of the n row ranges reads the count lists parts, keeping the triplets of its rows (AllInRange: every
  // triplet is of its rows, n == 1).
  template <bool AllInRange>
  const CsrMatrix& build_ranges(int rows, int cols, int n, const std::vector<Triplet>* parts, std::size_t count);
  void merge_rows(const CompressedRows& r, std::size_t at);

  CsrMatrix matrix_;
  bool kept_pattern_ = false;
  std::vector<std::unique_ptr<CompressedRows>> ranges_;  // one per thread
  InPlaceSum in_place_sum_;
  RowSum row_sum_;
  int summed_cols_ = 0;
  std::vector<char> range_kept_;  // per range: were its rows summed in place?
  CsrMatrix merged_;              // build_on_last_pattern's output, then the matrix's former arrays
};

// One build, without keeping the buffers.
CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts);

}  // namespace dlmfsi
