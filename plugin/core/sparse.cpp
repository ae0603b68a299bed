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
  // Counting sort by row, then sort and merge each row.
  std::vector<int> offset(rows + 1, 0);
  for (const auto& p : parts)
    for (const Triplet& t : p) ++offset[t.row + 1];
  for (int i = 0; i < rows; ++i) offset[i + 1] += offset[i];
  std::vector<std::pair<int, double>> bucket(offset.back());
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for (const auto& p : parts)
    for (const Triplet& t : p) bucket[fill[t.row]++] = {t.col, t.value};

  CsrMatrix m;
  m.rows = rows;
  m.cols = cols;
  m.start.assign(rows + 1, 0);
  m.column.reserve(bucket.size());
  m.value.reserve(bucket.size());
  for (int i = 0; i < rows; ++i) {
    auto b = bucket.begin() + offset[i], e = bucket.begin() + offset[i + 1];
    std::sort(b, e, [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto it = b; it != e; ++it) {
      if (!m.column.empty() && static_cast<int>(m.column.size()) > m.start[i] && m.column.back() == it->first)
        m.value.back() += it->second;
      else {
        m.column.push_back(it->first);
        m.value.push_back(it->second);
      }
    }
    m.start[i + 1] = static_cast<int>(m.column.size());
  }
  return m;
}

}  // namespace dlmfsi
