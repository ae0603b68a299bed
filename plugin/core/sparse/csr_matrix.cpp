#include "sparse/csr_matrix.hpp"

#include <algorithm>

namespace dlmfsi {

double CsrMatrix::at(int i, int j) const {
  auto b = column.begin() + start[i], e = column.begin() + start[i + 1];
  auto it = std::lower_bound(b, e, j);
  return it != e && *it == j ? value[it - column.begin()] : 0.0;
}

}  // namespace dlmfsi
