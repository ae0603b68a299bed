#include "sparse.hpp"

#include <algorithm>
#include <utility>

namespace dlmfsi {

double CsrMatrix::at(int i, int j) const {
  auto b = column.begin() + start[i], e = column.begin() + start[i + 1];
  auto it = std::lower_bound(b, e, j);
  return it != e && *it == j ? value[it - column.begin()] : 0.0;
}

CsrMatrix compress(int rows, int cols, const std::vector<std::vector<Triplet>>& parts) {
  // Counting sort by row (stable: the parts' order is kept within a row, so sums come out the same for any
  // thread count), then per row duplicates summed through a column -> position table, and the row's few
  // distinct columns sorted.
  std::vector<int> offset(rows + 1, 0);
  for (const auto& p : parts)
    for (const Triplet& t : p) ++offset[t.row + 1];
  for (int i = 0; i < rows; ++i) offset[i + 1] += offset[i];
  std::vector<int> bucket_col(offset.back());
  std::vector<double> bucket_value(offset.back());
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for (const auto& p : parts)
    for (const Triplet& t : p) {
      const int at = fill[t.row]++;
      bucket_col[at] = t.col;
      bucket_value[at] = t.value;
    }

  CsrMatrix m;
  m.rows = rows;
  m.cols = cols;
  m.start.assign(rows + 1, 0);
  m.column.reserve(bucket_col.size());
  m.value.reserve(bucket_col.size());
  std::vector<int> position(cols, -1);  // where column c sits in m.column, if in the current row
  std::vector<std::pair<int, double>> row;
  for (int i = 0; i < rows; ++i) {
    const int begin = static_cast<int>(m.column.size());
    for (int e = offset[i]; e < offset[i + 1]; ++e) {
      const int c = bucket_col[e];
      if (position[c] >= begin) {
        m.value[position[c]] += bucket_value[e];
      } else {
        position[c] = static_cast<int>(m.column.size());
        m.column.push_back(c);
        m.value.push_back(bucket_value[e]);
      }
    }
    // the row by column: insertion sort for the usual handful of entries, std::sort for long rows (a
    // solid much coarser than the fluid)
    const int end = static_cast<int>(m.column.size());
    if (end - begin > 32) {
      row.clear();
      for (int k = begin; k < end; ++k) row.emplace_back(m.column[k], m.value[k]);
      std::sort(row.begin(), row.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (int k = begin; k < end; ++k) {
        m.column[k] = row[k - begin].first;
        m.value[k] = row[k - begin].second;
      }
    } else {
      for (int k = begin + 1; k < end; ++k) {
        const int c = m.column[k];
        const double v = m.value[k];
        int j = k;
        for (; j > begin && m.column[j - 1] > c; --j) {
          m.column[j] = m.column[j - 1];
          m.value[j] = m.value[j - 1];
        }
        m.column[j] = c;
        m.value[j] = v;
      }
    }
    m.start[i + 1] = static_cast<int>(m.column.size());
  }
  return m;
}

}  // namespace dlmfsi
