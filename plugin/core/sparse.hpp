// Sparse matrices: triplets gathered during assembly, compressed rows as the result.
#pragma once
#include <memory>
#include <utility>
#include <vector>

namespace dlmfsi {

struct Triplet {
  int row, col;
  double value;
};

struct CsrMatrix {
  int rows = 0, cols = 0;
  std::vector<int> start;  // rows + 1 offsets
  std::vector<int> column;
  std::vector<double> value;
  double at(int i, int j) const;  // 0 where there is no entry
};

// Compressed rows from triplets, the buffers kept from one build to the next (grown, never shrunk), so
// that a time loop takes no fresh memory. Duplicate (row, col) entries are summed in the order given (the
// parts in order, each in its order) and the columns sorted within each row; linear in the number of
// triplets plus the sorts of each row's distinct columns. When the triplets fall on the last build's
// pattern and cover all of it, the values are summed in place in the same order (the same sums bit for
// bit) and the pattern is kept. With threads, each compresses a range of rows (reading every triplet, in
// order): the same matrix for any thread count.
class CsrBuilder {
 public:
  CsrBuilder();
  ~CsrBuilder();
  CsrBuilder(const CsrBuilder&) = delete;
  CsrBuilder& operator=(const CsrBuilder&) = delete;
  const CsrMatrix& build(int rows, int cols, const std::vector<std::vector<Triplet>>& parts, int threads = 1);
  const CsrMatrix& matrix() const { return matrix_; }
  // Did the last build keep the pattern of the one before?
  bool kept_pattern() const { return kept_pattern_; }
  // The matrix moved out (the builder starts afresh).
  CsrMatrix release() { return std::exchange(matrix_, CsrMatrix{}); }

 private:
  struct Rows;  // a range of rows with one thread's buffers
  bool sum_in_place(Rows& rows, const std::vector<std::vector<Triplet>>& parts);
  // AllRows: one range of all the rows (no triplet to skip).
  template <bool AllRows>
  void compress(Rows& rows, int cols, const std::vector<std::vector<Triplet>>& parts);
  CsrMatrix matrix_;
  bool kept_pattern_ = false;
  std::vector<std::unique_ptr<Rows>> ranges_;
  std::vector<unsigned> stamp_;  // per entry: the build that last summed into it
  unsigned stamp_value_ = 0;
};

// One build, without keeping the buffers.
CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts);

}  // namespace dlmfsi
