// Sparse matrices: triplets gathered during assembly, compressed rows as the result.
#pragma once
#include <vector>

namespace dlmfsi {

struct Triplet {
  int row, col;
  double value;
};

// Row i holds the entries start[i] .. start[i + 1] - 1: columns column[e] (increasing) and values value[e].
struct CsrMatrix {
  int rows = 0, cols = 0;
  std::vector<int> start;  // rows + 1 offsets
  std::vector<int> column;
  std::vector<double> value;
  double at(int i, int j) const;  // 0 where there is no entry
};

}  // namespace dlmfsi
