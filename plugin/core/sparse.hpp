// Sparse matrices: triplets gathered during assembly, compressed rows as the result.
#pragma once
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

// Sums duplicate (row, col) entries, in the order given; columns sorted within each row. Linear in the
// number of triplets plus the sorts of each row's distinct columns.
CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts);

}  // namespace dlmfsi
