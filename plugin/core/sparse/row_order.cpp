#include "sparse/row_order.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "errors.hpp"

namespace dlmfsi {

void sort_by_rows(int rows, std::size_t count, int* row, int* col, double* value, int base) {
  std::vector<std::size_t> start(static_cast<std::size_t>(rows) + 1, 0);
  for (std::size_t k = 0; k < count; ++k) {
    const long r = static_cast<long>(row[k]) - base;
    if (r < 0 || r >= rows)
      throw Error("sort: entry " + std::to_string(k) + " in row " + std::to_string(row[k]) + ", outside rows " +
                  std::to_string(base) + " to " + std::to_string(base + rows - 1));
    ++start[r + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  // order[p]: the entry at place p in row order (within a row, columns ascending after the sorts below)
  std::vector<std::size_t> order(count), next(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < count; ++k) order[next[row[k] - base]++] = k;
  for (int r = 0; r < rows; ++r)
    std::sort(order.begin() + start[r], order.begin() + start[r + 1],
              [&](std::size_t a, std::size_t b) { return col[a] < col[b]; });
  std::vector<int> c(count);
  std::vector<double> v(count);
  for (std::size_t k = 0; k < count; ++k) {
    c[k] = col[order[k]];
    v[k] = value[order[k]];
  }
  for (int r = 0; r < rows; ++r)
    for (std::size_t k = start[r]; k < start[r + 1]; ++k) row[k] = r + base;
  std::copy(c.begin(), c.end(), col);
  std::copy(v.begin(), v.end(), value);
}

}  // namespace dlmfsi
