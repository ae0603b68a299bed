// Sparse matrices: triplets gathered during assembly, compressed rows as the result.
#pragma once
#include <vector>

#include "buffer_room.hpp"
#include "parallel/shares.hpp"

namespace dlmfsi {

struct Triplet {
  int row, col;
  double value;
  Triplet() = default;
  Triplet(int r, int c, double v) : row(r), col(c), value(v) {}
};

// The rows 0 .. rows - 1 split into n consecutive ranges, one per compressing thread: range t holds the
// rows first(t) .. first(t + 1) - 1.
struct RowRanges {
  int rows = 0, n = 1;
  int first(int t) const { return static_cast<int>(share_first(rows, t, n)); }
  // The range holding row.
  int of(int row) const { return share_of(rows, row, n); }
};

// Row i holds the entries start[i] .. start[i + 1] - 1: columns column[e] (increasing) and values value[e].
struct CsrMatrix {
  int rows = 0, cols = 0;
  std::vector<int> start;  // rows + 1 offsets
  BigVector<int> column;  // (BigVector: buffer_room.hpp; a large matrix's fresh pages are huge ones)
  BigVector<double> value;
  double at(int i, int j) const;  // 0 where there is no entry
};

}  // namespace dlmfsi
